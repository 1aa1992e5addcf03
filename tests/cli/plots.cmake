# Plots (src/spectral/io/gnuplot_process.h): hostile plot paths and spectrum file names run no command and leave
# nothing behind; a plot that cannot be written is refused before anything else is written.
foreach(plots_case light upsample gamut inspect bad-folder)
  add_test(NAME "cli: plots ${plots_case}: no shell, no leftovers"
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/plots_security.sh ${plots_case}
                   $<TARGET_FILE:rimu-light> $<TARGET_FILE:rimu-colour>)
endforeach()
# Plot outputs go through the renderer's output-file code: .jpg refused, devices written by a checked copy and kept.
add_test(NAME "cli: plots: format by name, a full device is exit 2 and stays a device"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/plot_outputs.sh $<TARGET_FILE:rimu-light> $<TARGET_FILE:rimu-colour>
                 ${PROJECT_SOURCE_DIR}/data/examples/downlight.ies)
