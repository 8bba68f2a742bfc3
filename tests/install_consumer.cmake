# ctest's `install_consumer` test (CMakeLists.txt): the library as an outside project meets it, built
# from docs/library.md exactly as the page shows it.
#  1. `cmake --install` of this build (component `library`) into WORK_DIR/prefix;
#  2. the page's ```cmake block becomes the project's CMakeLists.txt and its ```cpp block main.cpp;
#  3. the project configures (find_package(physarum) against the prefix alone: no path into the
#     source or build tree), builds and runs; the program must write what the page says (state.bin).
#
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_consumer.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/project" "${WORK_DIR}/run")

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "install_consumer: ${what} failed (${status}):\n${out}\n${err}")
  endif()
endfunction()

# The first ```LANGUAGE block of docs/library.md, as written.
file(READ "${SOURCE_DIR}/docs/library.md" page)
function(block_of language out_var)
  string(FIND "${page}" "```${language}\n" begin)
  if(begin EQUAL -1)
    message(FATAL_ERROR "install_consumer: docs/library.md has no ```${language} block")
  endif()
  string(LENGTH "```${language}\n" fence)
  math(EXPR begin "${begin} + ${fence}")
  string(SUBSTRING "${page}" ${begin} -1 rest)
  string(FIND "${rest}" "```" end)
  string(SUBSTRING "${rest}" 0 ${end} block)
  set(${out_var} "${block}" PARENT_SCOPE)
endfunction()
block_of(cpp program)
block_of(cmake project)
file(WRITE "${WORK_DIR}/project/main.cpp" "${program}")
file(WRITE "${WORK_DIR}/project/CMakeLists.txt" "${project}")
string(REGEX MATCH "add_executable\\(([A-Za-z0-9_]+)" executable "${project}")
set(executable "${CMAKE_MATCH_1}")

run_step("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix" --component library)
run_step("configuring docs/library.md's project" ${CMAKE_COMMAND} -S "${WORK_DIR}/project" -B "${WORK_DIR}/build"
         -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run_step("building docs/library.md's project" ${CMAKE_COMMAND} --build "${WORK_DIR}/build")
execute_process(COMMAND "${WORK_DIR}/build/${executable}" WORKING_DIRECTORY "${WORK_DIR}/run"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "install_consumer: ${executable} exited ${status}:\n${out}\n${err}")
endif()
if(NOT EXISTS "${WORK_DIR}/run/state.bin")
  message(FATAL_ERROR "install_consumer: ${executable} ran but wrote no state.bin:\n${out}\n${err}")
endif()
message(STATUS "install_consumer: ${executable} built against ${WORK_DIR}/prefix and ran:\n${err}")
