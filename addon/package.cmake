# cmake -DSOURCE=addon/vesselmesh -DSTAGE=dir -DNATIVE=vesselmesh_core.so -DLICENSE=LICENSE -DZIP=out.zip -DPROJECT_VERSION=...
#       -P package.cmake
# Stages the add-on afresh (so that deleted sources do not linger) and zips it with one top-level folder.
file(REMOVE_RECURSE ${STAGE})
file(COPY ${SOURCE} DESTINATION ${STAGE} FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
foreach(template __init__.py blender_manifest.toml)
  configure_file(${SOURCE}/${template}.in ${STAGE}/vesselmesh/${template} @ONLY)
endforeach()
file(COPY ${NATIVE} DESTINATION ${STAGE}/vesselmesh/_native)
file(COPY ${LICENSE} DESTINATION ${STAGE}/vesselmesh)
file(REMOVE ${ZIP})
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${ZIP} --format=zip vesselmesh WORKING_DIRECTORY ${STAGE}
                RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "could not write ${ZIP}")
endif()
