# Plot and sweep scripts (tools/) on synthetic run directories; needs /usr/bin/python3 with numpy and matplotlib.
add_test(NAME plot_tools COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_plots.sh ${CMAKE_BINARY_DIR}/plot_test)
set_tests_properties(plot_tools PROPERTIES TIMEOUT 300)
# The run queues (tools/show_it_runs.sh, tools/campaign_runs.sh) with a stand-in binary.
add_test(NAME run_queues COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_run_queues.sh ${CMAKE_BINARY_DIR}/run_queues_test)
set_tests_properties(run_queues PROPERTIES TIMEOUT 60)
# The lift-map tool (tools/eulerfsi_liftmap.py) with a stand-in binary whose lift is known.
add_test(NAME liftmap_tool COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_liftmap.sh ${CMAKE_BINARY_DIR}/liftmap_test)
set_tests_properties(liftmap_tool PROPERTIES TIMEOUT 120)
# The regime-map tool (tools/eulerfsi_regime.py) with a stand-in binary whose lift is known per (Re, We).
add_test(NAME regime_tool COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_regime.sh ${CMAKE_BINARY_DIR}/regime_test)
set_tests_properties(regime_tool PROPERTIES TIMEOUT 120)
