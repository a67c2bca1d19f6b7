# The bad-input matrix: every broken or degenerate input through
# tmr_partition and tmr_mapper. Each run must end, within TIMEOUT seconds,
# either with exit code 0 (valid but degenerate input: a correct result) or
# with one line "TOOL: error: ..." on standard error and a non-zero exit;
# never with a signal, an abort or COLMAP's "Check failed". The input
# database must be byte-identical afterwards.
#   -DPARTITION=... -DMAPPER=... -DSYNTH=... -DSQLITE3=... -DWORK_DIR=...
#   [-DPYTHON3=...] (for the locked-database case)
#   [-DUNSHARE=...] (for the full-disk and read-only-filesystem cases: a
#   small tmpfs or a read-only bind mount in a mount namespace of its own;
#   skipped where mounting is not allowed)
cmake_minimum_required(VERSION 3.25)
set(TIMEOUT 180)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(good ${WORK_DIR}/good.db)
execute_process(
  COMMAND ${SYNTH} --database_path ${good} --model_path ${WORK_DIR}/gt
          --num_places 1 --num_unlinked_places 0 --cameras_per_place 20 --seed 3
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tmr_synth failed: ${err}")
endif()

set(failures "")
set(num_cases 0)

# Runs TOOL (partition or mapper) on DB with extra ARGS; EXPECT is "error",
# "ok" or "any" (a clear error or a result, for inputs where either is
# right, e.g. a locked database). A list in `wrapper`, if set, is put
# before the command. COLMAP's own log lines (glog: I/W/E and a date) do
# not count as the tool's error lines.
function(run_case name tool db expect)
  set(args ${ARGN})
  if(NOT "--output_path" IN_LIST args)
    list(APPEND args --output_path ${WORK_DIR}/out_${name})
  endif()
  if(tool STREQUAL "partition")
    set(command ${PARTITION} --database_path ${db} --picture 0)
    set(prefix "tmr_partition")
  else()
    set(command ${MAPPER} --database_path ${db})
    if(NOT "--Mapper.num_threads" IN_LIST args)
      list(APPEND args --Mapper.num_threads 2)
    endif()
    set(prefix "tmr_mapper")
  endif()
  set(hash_before "")
  if(EXISTS ${db} AND NOT IS_DIRECTORY ${db})
    file(SHA256 ${db} hash_before)
  endif()
  set(wal_hash_before "")
  if(EXISTS ${db}-wal AND NOT IS_DIRECTORY ${db}-wal)
    file(SHA256 ${db}-wal wal_hash_before)
  endif()
  execute_process(COMMAND ${wrapper} ${command} ${args} TIMEOUT ${TIMEOUT}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  math(EXPR n "${num_cases} + 1")
  set(num_cases ${n} PARENT_SCOPE)
  set(problem "")
  string(REGEX REPLACE "(^|\n)[IWE][0-9][0-9][0-9][0-9][0-9][0-9][0-9][0-9] [^\n]*"
         "" tool_err "${err}")
  # (a semicolon in a message would split it into two list items)
  string(REPLACE ";" "," error_text "${tool_err}")
  string(REGEX MATCHALL "[^\n]*error[^\n]*" error_lines "${error_text}")
  list(LENGTH error_lines num_error_lines)
  if(NOT rc MATCHES "^[0-9]+$")
    set(problem "did not exit normally: ${rc}")
  elseif(err MATCHES "Check failed|terminate called|Aborted|Segmentation|AddressSanitizer|runtime error")
    set(problem "crashed or failed a check")
  elseif(rc EQUAL 0 AND expect STREQUAL "error")
    set(problem "exit 0, expected an error")
  elseif(NOT rc EQUAL 0 AND expect STREQUAL "ok")
    set(problem "exit ${rc}, expected a result")
  elseif(NOT rc EQUAL 0 AND NOT (num_error_lines EQUAL 1 AND
                                 err MATCHES "(^|\n)${prefix}: error: [^\n]+\n"))
    set(problem "exit ${rc} without one clear error line")
  endif()
  if(hash_before)
    file(SHA256 ${db} hash_after)
    if(NOT hash_after STREQUAL hash_before)
      set(problem "${problem} the input database changed")
    endif()
  endif()
  if(wal_hash_before)
    file(SHA256 ${db}-wal wal_hash_after)
    if(NOT wal_hash_after STREQUAL wal_hash_before)
      set(problem "${problem} the input's -wal file changed")
    endif()
  endif()
  string(REGEX REPLACE "\n$" "" shown "${err}")
  if(problem)
    message(STATUS "FAIL ${name} (${tool}): ${problem}\n    stderr: ${shown}")
    set(failures "${failures} ${name}/${tool}" PARENT_SCOPE)
  else()
    string(REGEX MATCH "[^\n]*error:[^\n]*" shown_error "${tool_err}")
    message(STATUS "ok   ${name} (${tool}): exit ${rc} ${shown_error}")
  endif()
endfunction()

# A copy of the good database changed by SQL.
function(make_db name sql)
  set(db ${WORK_DIR}/${name}.db)
  file(COPY_FILE ${good} ${db})
  execute_process(COMMAND ${SQLITE3} ${db} "${sql}" RESULT_VARIABLE rc
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cannot make ${name}: ${err}")
  endif()
endfunction()

function(run_both name expect)
  run_case(${name} partition ${WORK_DIR}/${name}.db ${expect} ${ARGN})
  run_case(${name} mapper ${WORK_DIR}/${name}.db ${expect} ${ARGN})
  set(failures "${failures}" PARENT_SCOPE)
  set(num_cases ${num_cases} PARENT_SCOPE)
endfunction()

# Files that are no database.
file(WRITE ${WORK_DIR}/empty.db "")
file(WRITE ${WORK_DIR}/text.db "this is not a database\n")
string(REPEAT "SQLite format 3\\0" 300 junk)
file(WRITE ${WORK_DIR}/header_only.db "${junk}")
run_both(missing error)
foreach(name empty text header_only)
  run_both(${name} error)
endforeach()
run_case(folder partition ${WORK_DIR} error)

# SQLite files with the wrong content.
make_db(foreign_schema "DROP TABLE images; DROP TABLE cameras; DROP TABLE keypoints;
  DROP TABLE descriptors; DROP TABLE matches; DROP TABLE two_view_geometries;
  CREATE TABLE notes (x TEXT);")
make_db(no_geometries "DROP TABLE two_view_geometries;")
make_db(no_images_table "DROP TABLE images;")
make_db(keypoints_truncated "UPDATE keypoints SET data = substr(data, 1, 7);")
make_db(keypoints_rows_too_large "UPDATE keypoints SET rows = rows * 1000 WHERE image_id = 2;")
make_db(matches_rows_too_large "UPDATE two_view_geometries SET rows = rows + 1000;")
make_db(matches_truncated "UPDATE two_view_geometries SET data = substr(data, 1, 5);")
make_db(match_beyond_keypoints "UPDATE two_view_geometries SET data = zeroblob(rows * 8)
  WHERE pair_id = (SELECT MIN(pair_id) FROM two_view_geometries);
  UPDATE keypoints SET rows = 0, data = NULL WHERE image_id = 1;")
make_db(negative_image_id "PRAGMA ignore_check_constraints = ON; UPDATE images SET image_id = -5 WHERE image_id = 2;")
make_db(huge_pair_id "INSERT INTO two_view_geometries (pair_id, rows, cols, data, config)
  VALUES (9223372036854775807, 20, 2, zeroblob(160), 2);")
make_db(pair_of_unknown_image "INSERT INTO two_view_geometries (pair_id, rows, cols, data, config)
  VALUES (2147483647 * 1 + 99999, 20, 2, zeroblob(160), 2);")
make_db(bad_camera_model "UPDATE cameras SET model = 99;")
make_db(bad_camera_params "UPDATE cameras SET params = zeroblob(3);")
foreach(name foreign_schema no_geometries no_images_table matches_rows_too_large
        matches_truncated negative_image_id huge_pair_id pair_of_unknown_image)
  run_both(${name} error)
endforeach()
# The partition reads no keypoints and no cameras: it may succeed.
foreach(name keypoints_truncated keypoints_rows_too_large match_beyond_keypoints
        bad_camera_model bad_camera_params)
  run_case(${name} partition ${WORK_DIR}/${name}.db any)
  run_case(${name} mapper ${WORK_DIR}/${name}.db error)
endforeach()

# COLMAP 4's rig and frame tables, broken: tmr does not read rigs and
# frames (its tasks get trivial ones), so these map as the good database
# does. NULL where data is required: a clear error; NULL matrices and
# relative poses (4.x writes them for what it did not estimate): a result.
make_db(frames_without_rig "DELETE FROM rigs;")
make_db(frame_data_of_missing_image "INSERT INTO frame_data VALUES(1, 99999, 1, 0);")
make_db(sensor_of_missing_rig "INSERT INTO rig_sensors VALUES(999, 77, 0, NULL);")
make_db(null_matrices "UPDATE two_view_geometries SET F = NULL, E = NULL, H = NULL,
  qvec = NULL, tvec = NULL;")
make_db(null_inlier_data "UPDATE two_view_geometries SET data = NULL;")
make_db(null_keypoint_data "UPDATE keypoints SET data = NULL WHERE image_id = 1;")
make_db(null_camera_params "UPDATE cameras SET params = NULL;")
foreach(name frames_without_rig frame_data_of_missing_image sensor_of_missing_rig
        null_matrices)
  run_both(${name} ok)
endforeach()
run_both(null_inlier_data error)
foreach(name null_keypoint_data null_camera_params)
  run_case(${name} partition ${WORK_DIR}/${name}.db any)
  run_case(${name} mapper ${WORK_DIR}/${name}.db error)
endforeach()

# A COLMAP 4 database in WAL mode whose verified pairs sit only in its -wal
# file (the writer was killed before a checkpoint): read through the WAL, a
# result, neither file changed. Without its -wal file the database holds no
# pairs (a clear error for the mapper); a -wal that cannot be read (a
# folder in its place) is a clear error, not a silent read of the database
# file without its changes.
if(PYTHON3)
  execute_process(COMMAND ${PYTHON3} -c
    "import shutil, sqlite3, sys
good, work = sys.argv[1], sys.argv[2]
shutil.copy(good, work + '/wal_writer.db')
c = sqlite3.connect(work + '/wal_writer.db', isolation_level=None)
c.execute('PRAGMA journal_mode = WAL')
c.execute('DELETE FROM two_view_geometries')
c.execute('PRAGMA wal_checkpoint(TRUNCATE)')
c.execute('PRAGMA wal_autocheckpoint = 0')
c.execute('ATTACH DATABASE ? AS good', (good,))
c.execute('INSERT INTO two_view_geometries SELECT * FROM good.two_view_geometries')
c.execute('DETACH DATABASE good')
for name in ('wal_pending', 'wal_missing', 'wal_unreadable'):
    shutil.copy(work + '/wal_writer.db', work + '/' + name + '.db')
shutil.copy(work + '/wal_writer.db-wal', work + '/wal_pending.db-wal')
c.close()"
    ${good} ${WORK_DIR} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cannot make the WAL databases: ${err}")
  endif()
  file(MAKE_DIRECTORY ${WORK_DIR}/wal_unreadable.db-wal)
  run_both(wal_pending ok)
  run_case(wal_missing partition ${WORK_DIR}/wal_missing.db ok)
  run_case(wal_missing mapper ${WORK_DIR}/wal_missing.db error)
  run_both(wal_unreadable error)
endif()

# Valid but degenerate.
make_db(no_matches "DELETE FROM two_view_geometries; DELETE FROM matches;")
make_db(single_image "DELETE FROM images WHERE image_id > 1;
  DELETE FROM two_view_geometries; DELETE FROM matches;")
make_db(no_images "DELETE FROM images; DELETE FROM two_view_geometries; DELETE FROM matches;")
make_db(weak_pairs_only "UPDATE two_view_geometries SET rows = 3, data = substr(data, 1, 24);")
# The partition of images without pairs is all unclustered images, a
# correct result; a mapper run has nothing to reconstruct.
foreach(name no_matches single_image weak_pairs_only)
  run_case(${name} partition ${WORK_DIR}/${name}.db ok)
  run_case(${name} mapper ${WORK_DIR}/${name}.db error)
endforeach()
run_both(no_images error)

# Output locations and options (on the good database).
run_case(output_under_a_file mapper ${good} error --output_path ${good}/out)
run_case(output_in_proc mapper ${good} error --output_path /proc/tmr_out)
run_case(output_under_a_file partition ${good} error --output_path ${good}/out)
run_case(missing_image_folder mapper ${good} error --image_path ${WORK_DIR}/no_photos)
run_case(negative_kernel_size partition ${good} error --Tmr.max_kernel_size -3)
run_case(negative_kernel_size mapper ${good} error --Tmr.max_kernel_size -3)
run_case(alpha_below_one partition ${good} error --Tmr.alpha 0.5)
run_case(zero_layers mapper ${good} error --Tmr.kernel_layers 0)
run_case(nan_epsilon partition ${good} error --Tmr.epsilon nan)
run_case(negative_refine_points mapper ${good} error --Tmr.merge_refine_points_per_image -1)
run_case(negative_register_images mapper ${good} error --Tmr.merge_register_images -2)
run_case(text_for_number mapper ${good} error --Mapper.num_threads many)
run_case(zero_threads mapper ${good} error --Mapper.num_threads 0)
run_case(negative_inliers mapper ${good} error --Mapper.abs_pose_min_num_inliers -1)
run_case(forward_motion_above_one mapper ${good} error --Mapper.init_max_forward_motion 2)
run_case(one_local_ba_image mapper ${good} error --Mapper.ba_local_num_images 1)
run_case(negative_tolerance mapper ${good} error --Mapper.ba_global_function_tolerance -1)
run_case(huge_number partition ${good} error --Tmr.kernel_layers 99999999999999999999)
run_case(unknown_flag mapper ${good} error --Tmr.no_such_option 1)
run_case(negative_min_matches partition ${good} error --min_num_matches -1)
run_case(negative_memory_budget mapper ${good} error --Tmr.memory_budget -1)
# A memory budget too small for one task: said in one line before any task
# runs (no task result in the work folder), naming the task and its need.
run_case(memory_budget_too_small mapper ${good} error --Tmr.memory_budget 0.01)
execute_process(COMMAND ${MAPPER} --database_path ${good} --output_path ${WORK_DIR}/small_budget
                        --Tmr.memory_budget 0.01
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT ${TIMEOUT})
file(GLOB_RECURSE task_results ${WORK_DIR}/small_budget/.tmr_work/*.result)
if(NOT rc EQUAL 1 OR task_results OR NOT err MATCHES
   "^tmr_mapper: error: the memory budget of 0.01 GiB \\(--Tmr.memory_budget\\) is too small for task (kernel|leaf)[.0-9]+: about [0-9.]+ GiB for its [0-9]+ images, beside [0-9.]+ GiB of correspondences of all images; give --Tmr.memory_budget [0-9]+ or more\n$")
  message(STATUS "FAIL memory_budget_too_small: exit ${rc}, results '${task_results}', stderr: ${err}")
  set(failures "${failures} memory_budget_message")
endif()

# A full disk under the output folder, at several points of the run: while
# a task database is created (COLMAP's Database class), while task data is
# copied, while a task runs (2 MB). A clear error, nothing that looks
# like a finished model (no OUT/0, no report.json).
if(UNSHARE)
  set(mount_point ${WORK_DIR}/full_disk)
  file(MAKE_DIRECTORY ${mount_point})
  execute_process(COMMAND ${UNSHARE} -m sh -c
                  "mount -t tmpfs -o size=64k tmpfs ${mount_point}"
                  RESULT_VARIABLE mount_rc OUTPUT_QUIET ERROR_QUIET)
  if(mount_rc EQUAL 0)
    # Under the sanitizers: a known leak in COLMAP's Database on a full disk
    # (see full_disk_leaks.supp), suppressed by name for these cases only.
    set(saved_asan_options "$ENV{ASAN_OPTIONS}")
    set(saved_lsan_options "$ENV{LSAN_OPTIONS}")
    set(ENV{ASAN_OPTIONS} "$ENV{ASAN_OPTIONS}:fast_unwind_on_malloc=0")
    set(ENV{LSAN_OPTIONS} "suppressions=${CMAKE_CURRENT_LIST_DIR}/full_disk_leaks.supp")
    foreach(size 100k 600k 1200k 2m)
      # (No semicolons: CMake would split the script into list items.)
      set(wrapper ${UNSHARE} -m sh -c
          "mount -t tmpfs -o size=${size} tmpfs ${mount_point} && \"$0\" \"$@\"
rc=$?
if [ -e ${mount_point}/out/0 ] || [ -e ${mount_point}/out/report.json ]
then
  echo 'half-written model left' >&2
  exit 99
fi
exit $rc")
      run_case(disk_full_${size} mapper ${good} error
               --output_path ${mount_point}/out)
      unset(wrapper)
    endforeach()
    set(ENV{ASAN_OPTIONS} "${saved_asan_options}")
    set(ENV{LSAN_OPTIONS} "${saved_lsan_options}")

    # A read-only filesystem (a read-only bind mount, which binds root as
    # well): the database on it is read as it is, also one in WAL mode
    # (SQLite needs its -shm file writable: a clear error or a result); an
    # output folder on it is a clear error.
    set(ro_dir ${WORK_DIR}/read_only)
    file(MAKE_DIRECTORY ${ro_dir})
    file(COPY_FILE ${good} ${ro_dir}/database.db)
    file(COPY_FILE ${good} ${ro_dir}/wal.db)
    execute_process(COMMAND ${SQLITE3} ${ro_dir}/wal.db "PRAGMA journal_mode=WAL"
                    OUTPUT_QUIET)
    set(wrapper ${UNSHARE} -m sh -c
        "mount --bind ${ro_dir} ${ro_dir} && mount -o remount,bind,ro ${ro_dir} && \"$0\" \"$@\"")
    run_case(read_only_fs_db_partition partition ${ro_dir}/database.db ok)
    run_case(read_only_fs_db_mapper mapper ${ro_dir}/database.db ok)
    run_case(read_only_fs_wal_db mapper ${ro_dir}/wal.db any)
    run_case(read_only_fs_output mapper ${good} error
             --output_path ${ro_dir}/out)
    unset(wrapper)
  else()
    message(STATUS "skip full-disk and read-only cases: cannot mount here")
  endif()
endif()

# A database another process holds an exclusive lock on: a clear error or
# a result, within the timeout, never a hang.
if(PYTHON3)
  file(COPY_FILE ${good} ${WORK_DIR}/locked.db)
  execute_process(COMMAND ${PYTHON3} -c
    "import sqlite3,subprocess,sys,time
c = sqlite3.connect(sys.argv[1], isolation_level=None)
c.execute('BEGIN EXCLUSIVE')
c.execute('UPDATE images SET name = name')
r = subprocess.run(sys.argv[2:], capture_output=True, text=True, timeout=${TIMEOUT})
sys.stderr.write(r.stderr)
sys.exit(r.returncode if r.returncode >= 0 else 128 - r.returncode)"
    ${WORK_DIR}/locked.db ${PARTITION} --database_path ${WORK_DIR}/locked.db
    --output_path ${WORK_DIR}/out_locked --picture 0
    RESULT_VARIABLE rc ERROR_VARIABLE err)
  math(EXPR num_cases "${num_cases} + 1")
  if(rc GREATER 1 OR err MATCHES "Check failed|terminate called|Segmentation")
    message(STATUS "FAIL locked (partition): exit ${rc}: ${err}")
    set(failures "${failures} locked/partition")
  else()
    message(STATUS "ok   locked (partition): exit ${rc} ${err}")
  endif()
endif()

if(failures)
  message(FATAL_ERROR "bad-input cases failed:${failures}")
endif()
message(STATUS "all ${num_cases} bad-input cases ended cleanly")
