# End-to-end runs of the real binary on tiny cases.
set(REG ${CMAKE_CURRENT_SOURCE_DIR}/regression)
# 1 and 2 ranks agree to round-off: dp/dx is a difference of O(1) numbers ~1e-3 apart and KE
# sums 1e4 terms in a different order, so relative differences of ~1e-13 per step are expected;
# 1e-10 bounds 40 steps with a margin of 25, and a wrong halo or transpose gives O(1e-3).
foreach(c unsteady_pipe particle_pipe particle_pipe_frame particle_pipe_refmap particle_pipe_implicit particle_pipe_rigid)
  add_test(NAME rank_independence_${c}
           COMMAND bash ${REG}/rank_independence.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/${c}.toml
                   ${CMAKE_BINARY_DIR}/regression/rank_${c} --rtol 1e-10 --field-tol 1e-10)
  set_tests_properties(rank_independence_${c} PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" PROCESSORS 2)
endforeach()
# and on 4 ranks (oversubscribed here: one x-slab of 6 planes per rank)
add_test(NAME rank_independence_particle_pipe_np4
         COMMAND bash ${REG}/rank_independence.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/particle_pipe.toml
                 ${CMAKE_BINARY_DIR}/regression/rank_particle_np4 --rtol 1e-10 --field-tol 1e-10)
set_tests_properties(rank_independence_particle_pipe_np4 PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV};NP=4" PROCESSORS 2)
# a continued run matches the uninterrupted one bit for bit, on 1 rank (grid at rest) and on
# 2 ranks (grid following the particle: the frame's velocity and offset are part of the state)
foreach(np_case "1;particle_pipe" "2;particle_pipe_frame" "2;particle_pipe_refmap" "2;particle_pipe_implicit" "2;particle_pipe_rigid")
  list(GET np_case 0 np)
  list(GET np_case 1 c)
  add_test(NAME restart_bit_for_bit_np${np}_${c}
           COMMAND bash ${REG}/restart.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/${c}.toml
                   ${CMAKE_BINARY_DIR}/regression/restart_np${np}_${c} ${np})
  set_tests_properties(restart_bit_for_bit_np${np}_${c} PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" PROCESSORS ${np})
endforeach()
# rows every 3 steps report the forces' mean since the previous row: a checkpoint (every 10 or 5
# steps) falls inside an interval, whose impulse it must carry
add_test(NAME restart_bit_for_bit_rows_every_3_np1_particle_pipe_refmap
         COMMAND bash ${REG}/restart.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/particle_pipe_refmap.toml
                 ${CMAKE_BINARY_DIR}/regression/restart_every3_refmap 1 --set output.every=3)
set_tests_properties(restart_bit_for_bit_rows_every_3_np1_particle_pipe_refmap PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}")
# the same with FFTW_MEASURE plans, whose choices may differ between processes: the restart reuses
# the wisdom stored beside the checkpoint (pressure on 1 rank; pressure and Helmholtz on 2)
foreach(np_case "1;particle_pipe" "2;particle_pipe_implicit")
  list(GET np_case 0 np)
  list(GET np_case 1 c)
  add_test(NAME restart_bit_for_bit_measure_np${np}_${c}
           COMMAND bash ${REG}/restart.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/${c}.toml
                   ${CMAKE_BINARY_DIR}/regression/restart_measure_np${np}_${c} ${np} --set solver.fft_planning=measure)
  set_tests_properties(restart_bit_for_bit_measure_np${np}_${c} PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" PROCESSORS ${np})
endforeach()
# every bad input refused with one clear message, a non-zero exit and nothing overwritten
add_test(NAME bad_input_refused
         COMMAND bash ${REG}/bad_input.sh $<TARGET_FILE:eulerfsi> ${CMAKE_CURRENT_SOURCE_DIR}
                 ${CMAKE_BINARY_DIR}/regression/bad_input)
set_tests_properties(bad_input_refused PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" PROCESSORS 2)
# the figure scripts on the output of a real run
add_test(NAME plots_from_real_run
         COMMAND bash ${REG}/plot_real_run.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/particle_pipe.toml
                 ${CMAKE_BINARY_DIR}/regression/plot_real_run)
set_tests_properties(plots_from_real_run PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}")
# ParaView opens our fields.xdmf and renders the particle in the pipe (tools/render_3d.sh)
add_test(NAME render_3d_from_real_run
         COMMAND bash ${REG}/render_3d.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/particle_pipe_refmap.toml
                 ${CMAKE_BINARY_DIR}/regression/render_3d)
set_tests_properties(render_3d_from_real_run PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" SKIP_RETURN_CODE 77 TIMEOUT 600)
# a restart by a version with other particle.csv columns keeps one header for every row
add_test(NAME restart_with_other_columns
         COMMAND bash ${REG}/restart_columns.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/particle_pipe.toml
                 ${CMAKE_BINARY_DIR}/regression/restart_columns)
set_tests_properties(restart_with_other_columns PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}")
# a disk that fills mid-run: exit 1 with one message, the last checkpoint kept and continued bit for
# bit, no half-written file, no crash in the HDF5/MPI clean-up (on 1 rank, and on 2 with the moving grid)
foreach(np_case "1;particle_pipe" "2;particle_pipe_frame")
  list(GET np_case 0 np)
  list(GET np_case 1 c)
  add_test(NAME disk_full_np${np}_${c}
           COMMAND bash ${REG}/disk_full.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/${c}.toml
                   ${CMAKE_BINARY_DIR}/regression/disk_full_np${np}_${c} ${np})
  set_tests_properties(disk_full_np${np}_${c} PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" PROCESSORS ${np})
endforeach()
