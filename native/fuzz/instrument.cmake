# Included by native/CMakeLists.txt when VESSELMESH_FUZZ is on, before any target is defined: every
# object of this build (the core library, the CLI, the fuzz targets) is compiled with libFuzzer's
# coverage instrumentation (but Eigen's: coverage_ignore.txt), AddressSanitizer and UBSan. Only the fuzz
# targets link libFuzzer itself (native/fuzz/CMakeLists.txt). Use a build folder of its own (scripts/fuzz.sh
# uses build/fuzz). The ignore list is a file the flags name, not a source: after changing it, build clean.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "VESSELMESH_FUZZ needs clang (libFuzzer), found ${CMAKE_CXX_COMPILER_ID}: "
                      "configure with CC=clang-14 CXX=clang++-14, or run scripts/fuzz.sh")
endif()
if(VESSELMESH_PYTHON)
  message(FATAL_ERROR "VESSELMESH_FUZZ instruments the whole build: configure it with -DVESSELMESH_PYTHON=OFF")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                    -fsanitize-coverage-ignorelist=${CMAKE_CURRENT_LIST_DIR}/coverage_ignore.txt
                    -fno-omit-frame-pointer -g)
add_link_options(-fsanitize=address,undefined)
