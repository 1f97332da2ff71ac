# Plot and sweep scripts (tools/) on synthetic run directories; needs /usr/bin/python3 with numpy and matplotlib.
add_test(NAME plot_tools COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/tools/test_plots.sh ${CMAKE_BINARY_DIR}/plot_test)
set_tests_properties(plot_tools PROPERTIES TIMEOUT 300)
