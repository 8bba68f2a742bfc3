# ctest's `read_exports` test (CMakeLists.txt): runs `physarum run` on small scenes and reads the
# outputs back with tests/read_exports.py under the Python environment tools/setup.sh creates, so the
# files are checked by readers that are not physarum's own (trimesh, a GLB parser from the spec).
#
#   cmake -DPHYSARUM_EXE=... -DPYTHON=... -DSCRIPT=... -DWORK_DIR=... -DSHARED_MESHES=... -P read_exports.cmake
#
# Scenes: a square (no UVs) always; spot.obj (UVs with seams, so result.glb has seam copies) when
# the shared meshes are there. 20 reference steps each: about a second in all.
foreach(var PHYSARUM_EXE PYTHON SCRIPT WORK_DIR SHARED_MESHES)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "read_exports.cmake: -D${var}=... is required")
  endif()
endforeach()

if(NOT EXISTS "${PYTHON}")
  message(FATAL_ERROR "read_exports: no Python environment at ${PYTHON}. Run `bash tools/setup.sh` "
                      "(it creates .venv with the pinned trimesh, numpy and pillow this test reads the outputs with).")
endif()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(parameters [["agents": 2000, "time_step": 0.01, "sensor_distance": 0.08, "sensor_angle": 15.0,
  "move_rate": 0.5, "turn_rate": 180.0, "turn_frequency": 20.0, "deposit_rate": 2.0, "decay_rate": 1.0,
  "diffuse_rate": 0.0001, "mean_lifetime": 1.0, "activation_time": 0.05, "integrator": "forward", "seed": 5]])
set(runs square)
file(WRITE "${WORK_DIR}/square.json" "{\"mesh\": \"shape:square\", \"scale_to_area\": 1.0, ${parameters}}\n")
if(EXISTS "${SHARED_MESHES}/spot.obj")
  list(APPEND runs spot)
  file(WRITE "${WORK_DIR}/spot.json" "{\"mesh\": \"${SHARED_MESHES}/spot.obj\", \"scale_to_area\": 4.0, ${parameters}}\n")
else()
  message(STATUS "read_exports: ${SHARED_MESHES}/spot.obj absent: the mesh with UV seams is not checked")
endif()

set(run_dirs "")
foreach(name IN LISTS runs)
  execute_process(COMMAND "${PHYSARUM_EXE}" run "${WORK_DIR}/${name}.json" --backend reference --steps 20
                          --out "${WORK_DIR}/${name}"
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "read_exports: physarum run ${name}.json failed (${status}):\n${out}${err}")
  endif()
  list(APPEND run_dirs "${WORK_DIR}/${name}")
endforeach()

execute_process(COMMAND "${PYTHON}" "${SCRIPT}" ${run_dirs} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "read_exports: ${SCRIPT} found problems (exit ${status}); the run folders are kept in ${WORK_DIR}")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
