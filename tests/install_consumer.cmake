# ctest's `install_consumer` test (CMakeLists.txt): the library as an outside project meets it.
#  1. `cmake --install` of this build (component `library`) into WORK_DIR/prefix;
#  2. the first ```cpp block of docs/library.md, extracted as it is written, becomes the program;
#  3. tests/install_consumer/ (find_package(physarum), physarum::api) configures and builds it
#     against the prefix alone, with no path into the source or build tree;
#  4. the program runs in WORK_DIR/run and must write what the example says it writes (state.bin).
#
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_consumer.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/run")

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "install_consumer: ${what} failed (${status}):\n${out}\n${err}")
  endif()
endfunction()

run_step("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix" --component library)

file(READ "${SOURCE_DIR}/docs/library.md" doc)
string(FIND "${doc}" "```cpp\n" begin)
if(begin EQUAL -1)
  message(FATAL_ERROR "install_consumer: docs/library.md has no ```cpp block")
endif()
math(EXPR begin "${begin} + 7")
string(SUBSTRING "${doc}" ${begin} -1 rest)
string(FIND "${rest}" "```" end)
string(SUBSTRING "${rest}" 0 ${end} example)
file(WRITE "${WORK_DIR}/library_example.cpp" "${example}")

run_step("configuring the outside project" ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/install_consumer"
         -B "${WORK_DIR}/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
         -DEXAMPLE_SOURCE=${WORK_DIR}/library_example.cpp)
run_step("building docs/library.md's example" ${CMAKE_COMMAND} --build "${WORK_DIR}/build")
execute_process(COMMAND "${WORK_DIR}/build/library_example" WORKING_DIRECTORY "${WORK_DIR}/run"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "install_consumer: the example exited ${status}:\n${out}\n${err}")
endif()
if(NOT EXISTS "${WORK_DIR}/run/state.bin")
  message(FATAL_ERROR "install_consumer: the example ran but wrote no state.bin:\n${out}\n${err}")
endif()
message(STATUS "install_consumer: built against ${WORK_DIR}/prefix and ran:\n${err}")
