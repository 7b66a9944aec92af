# cmake -DSOURCE=addon/vesselmesh -DSTAGE=dir -DNATIVE=vesselmesh_core.so -DLICENSE=LICENSE -DZIP=out.zip
#       -DEXTENSION_ZIP=ext.zip -DEXTENSION_PLATFORM=linux-x64 -DPROJECT_VERSION=... -P package.cmake
# Stages the add-on afresh (so that deleted sources do not linger) and writes the add-on zip, with one
# top-level folder, and the extension package, with the same files at its top.
file(REMOVE_RECURSE ${STAGE})
file(COPY ${SOURCE} DESTINATION ${STAGE} FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
foreach(template __init__.py blender_manifest.toml)
  configure_file(${SOURCE}/${template}.in ${STAGE}/vesselmesh/${template} @ONLY)
endforeach()
file(COPY ${NATIVE} DESTINATION ${STAGE}/vesselmesh/_native)
file(COPY ${LICENSE} DESTINATION ${STAGE}/vesselmesh)

function(zip archive directory)
  file(REMOVE ${archive})
  file(GLOB entries RELATIVE ${directory} ${directory}/*)
  execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${archive} --format=zip ${entries} WORKING_DIRECTORY ${directory}
                  RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "could not write ${archive}")
  endif()
endfunction()

zip(${ZIP} ${STAGE})
zip(${EXTENSION_ZIP} ${STAGE}/vesselmesh)
