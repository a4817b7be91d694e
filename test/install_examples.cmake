# ctest script: installs the build into a temporary prefix, checks the installed headers (every
# public header of src/strata/ is there, no internal/ folder is, and every "strata/..." include
# of an installed header resolves inside the prefix), builds examples/ against the installed
# package (find_package(strata CONFIG REQUIRED COMPONENTS ...), one example per capability) and
# runs those that need no data beyond ../shared/data. Fails on any step's error.
#   -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DDATA_DIR=...
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${what}:\n${out}${err}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result})")
  endif()
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
set(include_dir "${prefix}/include")
run_step("install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")

# Every public header of the tree is installed; nothing from an internal/ folder is.
file(GLOB_RECURSE tree_headers RELATIVE "${SOURCE_DIR}/src" "${SOURCE_DIR}/src/strata/*.h")
set(missing "")
foreach(header ${tree_headers})
  if(NOT header MATCHES "/internal/" AND NOT EXISTS "${include_dir}/${header}")
    list(APPEND missing ${header})
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "public headers not installed: ${missing}")
endif()
file(GLOB_RECURSE installed_files LIST_DIRECTORIES true "${include_dir}/strata/*")
set(internal "")
foreach(path ${installed_files})
  if(path MATCHES "/internal(/|$)")
    list(APPEND internal ${path})
  endif()
endforeach()
if(internal)
  message(FATAL_ERROR "internal headers were installed: ${internal}")
endif()

# Every project include of an installed header resolves inside the prefix (no header reaches
# into one that stayed behind).
file(GLOB_RECURSE installed_headers "${include_dir}/strata/*.h")
list(LENGTH installed_headers installed_count)
set(dangling "")
foreach(header ${installed_headers})
  file(STRINGS "${header}" includes REGEX "^#include [\"<]strata/")
  foreach(line ${includes})
    string(REGEX REPLACE "^#include [\"<]([^\">]+)[\">].*" "\\1" included "${line}")
    if(NOT EXISTS "${include_dir}/${included}")
      file(RELATIVE_PATH name "${include_dir}" "${header}")
      list(APPEND dangling "${name} -> ${included}")
    endif()
  endforeach()
endforeach()
if(dangling)
  message(FATAL_ERROR "installed headers include what was not installed: ${dangling}")
endif()
message(STATUS "${installed_count} public headers installed, all includes resolve")

find_program(CCACHE ccache)
set(launcher "")
if(CCACHE)
  set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${CCACHE}")
endif()
run_step("configure examples" ${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples" -B "${WORK_DIR}/build" -G Ninja
         -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}" ${launcher})
run_step("build examples" ${CMAKE_COMMAND} --build "${WORK_DIR}/build" -j 2)
set(bin "${WORK_DIR}/build")

run_step("esdf_path" "${bin}/esdf_path")
run_step("lcm_pose" "${bin}/lcm_pose")
# A simulated session, fused by `strata fuse` into a saved map, a path planned on that map.
set(ENV{STRATA_WORLDS_DIR} "${SOURCE_DIR}/worlds")
run_step("simulate_session" "${bin}/simulate_session" room 0 "${WORK_DIR}/session" 30)
run_step("strata fuse (the map for plan_path)" "${BUILD_DIR}/bin/strata" fuse "${WORK_DIR}/session"
         --voxel-size 0.05 --free-space --map "${WORK_DIR}/room.strata" --quiet)
# Both ends in the free space these 30 frames observe, along the room's wall at x = 0.
run_step("plan_path" "${bin}/plan_path" "${WORK_DIR}/room.strata" 0.6,0.6,1.4 0.6,2.6,1.4 grid 0.2)
run_step("explore_world" "${bin}/explore_world" room 10)
if(EXISTS "${DATA_DIR}/redkitchen/rgb.txt")
  run_step("fuse_tum" "${bin}/fuse_tum" "${DATA_DIR}/redkitchen" "${WORK_DIR}/kitchen.ply" 0.05)
  if(NOT EXISTS "${WORK_DIR}/kitchen.ply")
    message(FATAL_ERROR "fuse_tum wrote no mesh")
  endif()
else()
  message(STATUS "fuse_tum not run: ${DATA_DIR}/redkitchen not found")
endif()
if(EXISTS "${DATA_DIR}/euroc_v101_micro")
  run_step("odometry_euroc" "${bin}/odometry_euroc" "${DATA_DIR}/euroc_v101_micro"
           "${WORK_DIR}/vio.txt")
  if(NOT EXISTS "${WORK_DIR}/vio.txt")
    message(FATAL_ERROR "odometry_euroc wrote no trajectory")
  endif()
else()
  message(STATUS "odometry_euroc not run: ${DATA_DIR}/euroc_v101_micro not found")
endif()
