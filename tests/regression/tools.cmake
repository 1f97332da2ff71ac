# Plot and sweep scripts (tools/) on synthetic run directories; needs /usr/bin/python3 with numpy and matplotlib.
add_test(NAME plot_tools COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_plots.sh ${CMAKE_BINARY_DIR}/plot_test)
set_tests_properties(plot_tools PROPERTIES TIMEOUT 300)
# The run queues of issues 9 and 11 (tools/show_it_runs.sh, tools/campaign_runs.sh) with a stand-in binary.
add_test(NAME run_queues COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_run_queues.sh ${CMAKE_BINARY_DIR}/run_queues_test)
set_tests_properties(run_queues PROPERTIES TIMEOUT 60)
