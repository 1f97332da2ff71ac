# End-to-end runs of the real binary on tiny cases.
set(REG ${CMAKE_CURRENT_SOURCE_DIR}/regression)
add_test(NAME rank_independence_pipe
         COMMAND bash ${REG}/rank_independence.sh $<TARGET_FILE:eulerfsi> ${REG}/cases/unsteady_pipe.toml
                 ${CMAKE_BINARY_DIR}/regression/rank_pipe)
set_tests_properties(rank_independence_pipe PROPERTIES ENVIRONMENT "${EULERFSI_TEST_ENV}" PROCESSORS 2)
