# Plots (src/spectral/gnuplot_process.h): hostile plot paths and spectrum file names run no command and leave
# nothing behind; a plot that cannot be written is refused before anything else is written.
foreach(plots_case light upsample gamut inspect bad-folder)
  add_test(NAME "cli: plots ${plots_case}: no shell, no leftovers"
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/plots_security.sh ${plots_case}
                   $<TARGET_FILE:rimu-light> $<TARGET_FILE:rimu-colour>)
endforeach()
