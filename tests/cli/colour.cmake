# rimu-colour: tristimulus methods, reflectance colorimetry and colour fidelity (contracts and published values).
set(colour_csv_dir ${CMAKE_CURRENT_SOURCE_DIR}/cli/colour)

# CIE 15:2004 Table T.8 xy (2°), 4 decimals: F2 (0.3721, 0.3751), F7 (0.3129, 0.3292), F11 (0.3805, 0.3769). The
# text report prints 5 decimals; the patterns accept exactly the 5-decimal values that round to the published 4.
rimu_cli_test("rimu-colour F2 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.372(0[5-9]|1[0-4]) 0\\.375(0[5-9]|1[0-4])"
              $<TARGET_FILE:rimu-colour> report F2)
rimu_cli_test("rimu-colour F7 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.312(8[5-9]|9[0-4]) 0\\.329(1[5-9]|2[0-4])" $<TARGET_FILE:rimu-colour> report F7)
rimu_cli_test("rimu-colour F11 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.380(4[5-9]|5[0-4]) 0\\.376(8[5-9]|9[0-4])" $<TARGET_FILE:rimu-colour> report F11)
rimu_cli_test("rimu-colour names the method of 5 nm data native" 0 "^tristimulus method native$"
              $<TARGET_FILE:rimu-colour> report F2)
rimu_cli_test("rimu-colour --method 1nm is named in the JSON" 0 "\"tristimulus_method\": \"1nm\""
              $<TARGET_FILE:rimu-colour> report F2 --method 1nm --json)
rimu_cli_test("rimu-colour unknown method" 1 "--method: unknown tristimulus method 'trapezoid'"
              $<TARGET_FILE:rimu-colour> report F2 --method trapezoid)
rimu_cli_test("rimu-colour native needs a table" 1 "continuous spectrum.*--method 1nm"
              $<TARGET_FILE:rimu-colour> report --blackbody 3000 --method native)
rimu_cli_test("rimu-colour E308 needs the short-wavelength tail" 1
              "ten_nm_from_400.csv.*ASTM E308 needs data from 380 nm or below|ASTM E308 needs data from 380 nm or below.*ten_nm_from_400.csv"
              $<TARGET_FILE:rimu-colour> report --csv ${colour_csv_dir}/ten_nm_from_400.csv)

# Reflectance colorimetry.
rimu_cli_test("rimu-colour reflectance of a ColorChecker patch uses E308 at 10 nm" 0
              "\"tristimulus_method\": \"astm-e308\"" $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --json)
rimu_cli_test("rimu-colour reflectance prints CIELAB" 0 "CIELAB +76\\.069 0\\.000 0\\.000"
              $<TARGET_FILE:rimu-colour> reflectance --csv ${colour_csv_dir}/grey_50_10nm.csv)
rimu_cli_test("rimu-colour reflectance against itself has dE00 0" 0 "ΔE00 \\(CIEDE2000\\) +0\\.000"
              $<TARGET_FILE:rimu-colour> reflectance --csv ${colour_csv_dir}/grey_50_10nm.csv
              --reference ${colour_csv_dir}/grey_50_10nm.csv --illuminant D65 --observer 10)
rimu_cli_test("rimu-colour reflectance unknown illuminant" 1 "unknown illuminant 'D66'"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --illuminant D66)
rimu_cli_test("rimu-colour reflectance above 1.5" 1 "percent_reflectance.csv:3: r: reflectance factor 45 is above 1.5"
              $<TARGET_FILE:rimu-colour> reflectance --csv ${colour_csv_dir}/percent_reflectance.csv)
rimu_cli_test("rimu-colour reflectance below 0" 1 "negative_reflectance.csv:3: r: reflectance factor -0.5 is negative"
              $<TARGET_FILE:rimu-colour> reflectance --csv ${colour_csv_dir}/negative_reflectance.csv)
rimu_cli_test("rimu-colour reflectance E308 needs data from 380 nm" 1 "ASTM E308 needs data from 380 nm or below"
              $<TARGET_FILE:rimu-colour> reflectance --csv ${colour_csv_dir}/ten_nm_from_400.csv)
rimu_cli_test("rimu-colour reflectance unknown patch" 1 "unknown ColorChecker patch 'dark skinn'.*bluish green"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skinn")
rimu_cli_test("rimu-colour reflectance bad observer" 1 "--observer: expected 2 or 10"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --observer 4)

# Colour fidelity (CIE 224:2017 / TM-30-20). CIE 2017 calculator: F2 Rf 70.1; TM-30-18 calculator: F2 Rg 86.
rimu_cli_test("rimu-colour fidelity of F2" 0 "Rf \\(CIE 224:2017\\) +70\\.1" $<TARGET_FILE:rimu-colour> fidelity F2)
rimu_cli_test("rimu-colour fidelity of F2 gamut" 0 "Rg \\(TM-30-20\\) +8[56]\\.[0-9]" $<TARGET_FILE:rimu-colour> fidelity F2)
rimu_cli_test("rimu-colour fidelity JSON has 16 bins" 0 "\"hue_bins\"" $<TARGET_FILE:rimu-colour> fidelity LED-B3 --json)
rimu_cli_test("rimu-colour fidelity needs 380-780 nm" 1 "380 to 780 nm"
              $<TARGET_FILE:rimu-colour> fidelity --csv ${colour_csv_dir}/ten_nm_from_400.csv)
rimu_cli_test("rimu-colour fidelity unknown illuminant" 1 "unknown illuminant 'F13'" $<TARGET_FILE:rimu-colour> fidelity F13)

# A flat 10 nm light is summed with the E308 weights of illuminant E: its chromaticity is E's, (1/3, 1/3) to the
# 1e-4 that the CMFs' own rounding gives (CIE 15: E at 1 nm is (0.33331, 0.33329)).
rimu_cli_test("rimu-colour 10 nm light uses E308" 0 "^tristimulus method astm-e308$"
              $<TARGET_FILE:rimu-colour> report --csv ${colour_csv_dir}/flat_10nm.csv)
rimu_cli_test("rimu-colour 10 nm flat light is white E" 0 "xy  \\(2°\\) +0\\.333[23][0-9] 0\\.333[23][0-9]"
              $<TARGET_FILE:rimu-colour> report --csv ${colour_csv_dir}/flat_10nm.csv)

# The TM-30 colour vector graphic: a PNG at the given path, titles through the plot runner's text helper, a bad
# destination refused (exit 1) before anything is computed or written.
add_test(NAME "cli: rimu-colour fidelity --graphic writes a PNG and refuses a bad folder"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/colour_graphic.sh $<TARGET_FILE:rimu-colour>)

# D55 and D75 (CIE daylight at 5503 K and 7504 K) and the E308 weights of D55, D75, F2, F7 and F11.
# CIE 15:2004 Table T.3: D55 xy (0.33242, 0.34743), 5 decimals, summed at the basis' 5 nm.
rimu_cli_test("rimu-colour D55 matches CIE 15 Table T.3" 0 "xy  \\(2°\\) +0\\.33242 0\\.34743"
              $<TARGET_FILE:rimu-colour> report D55)
rimu_cli_test("rimu-colour reflectance under D75 uses E308" 0 "^tristimulus method astm-e308$"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --illuminant D75)
rimu_cli_test("rimu-colour reflectance under F11 uses E308" 0 "^tristimulus method astm-e308$"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --illuminant F11)
rimu_cli_test("rimu-colour E308 weights are named when missing" 1
              "no ASTM E308 weights for illuminant 'F3'.*A, C, D50, D55, D65, D75, E, F2, F7, F11"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --illuminant F3)

# ASTM E308 Table 6 (data corrected for bandpass, the default) or Table 5 (--bandpass-corrected no): every report
# names the table; the switch is refused where no E308 weights are used.
rimu_cli_test("rimu-colour reflectance names E308 Table 6 by default" 0
              "^e308 weights +ASTM E308 Table 6 \\(weights for spectral data corrected for bandpass\\)$"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin")
rimu_cli_test("rimu-colour reflectance --bandpass-corrected no uses Table 5" 0
              "^e308 weights +ASTM E308 Table 5 \\(weights for spectral data not corrected for bandpass\\)$"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --bandpass-corrected no)
rimu_cli_test("rimu-colour reflectance JSON names the E308 table" 0 "\"e308_table\": 5"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --bandpass-corrected no --json)
rimu_cli_test("rimu-colour report of 10 nm light names the E308 table" 0 "\"e308_table\": 6"
              $<TARGET_FILE:rimu-colour> report --csv ${colour_csv_dir}/flat_10nm.csv --json)
rimu_cli_test("rimu-colour --bandpass-corrected takes yes or no" 1 "--bandpass-corrected: expected yes or no, got 'maybe'"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --bandpass-corrected maybe)
rimu_cli_test("rimu-colour --bandpass-corrected is refused without E308" 1
              "--bandpass-corrected: .*summed by the 'native' method"
              $<TARGET_FILE:rimu-colour> report F2 --bandpass-corrected no)
rimu_cli_test("rimu-colour report unknown illuminant" 1 "unknown illuminant 'D66'" $<TARGET_FILE:rimu-colour> report D66)

# Illuminant C (CIE 15:2004 Table T.1, 5 nm): CIE 15:2004 Table T.3 xy (0.31006, 0.31616) to 4 decimals (0.3101,
# 0.3162): the native sum includes C's 360-375 nm values, which T.3's 380-780 nm sum leaves out (y 0.31617; the
# 5 decimals over 380-780 nm are checked in tests/spectral/e308_tables_test.cpp).
rimu_cli_test("rimu-colour C matches CIE 15 Table T.3" 0
              "xy  \\(2°\\) +0\\.310(0[5-9]|1[0-4]) 0\\.316(1[5-9]|2[0-4])" $<TARGET_FILE:rimu-colour> report C)
rimu_cli_test("rimu-colour reflectance under C uses E308" 0 "^tristimulus method astm-e308$"
              $<TARGET_FILE:rimu-colour> reflectance --patch "dark skin" --illuminant C)

# The other nine F illuminants of CIE 15:2004 Table T.8 (2°, 4 decimals) through the CLI as well (the library test
# checks all twelve): each pattern lists the ten 5-decimal values that round to the published pair.
rimu_cli_test("rimu-colour F1 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(31305|31306|31307|31308|31309|31310|31311|31312|31313|31314) 0\\.(33705|33706|33707|33708|33709|33710|33711|33712|33713|33714)" $<TARGET_FILE:rimu-colour> report F1)
rimu_cli_test("rimu-colour F3 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(40905|40906|40907|40908|40909|40910|40911|40912|40913|40914) 0\\.(39405|39406|39407|39408|39409|39410|39411|39412|39413|39414)" $<TARGET_FILE:rimu-colour> report F3)
rimu_cli_test("rimu-colour F4 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(44015|44016|44017|44018|44019|44020|44021|44022|44023|44024) 0\\.(40305|40306|40307|40308|40309|40310|40311|40312|40313|40314)" $<TARGET_FILE:rimu-colour> report F4)
rimu_cli_test("rimu-colour F5 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(31375|31376|31377|31378|31379|31380|31381|31382|31383|31384) 0\\.(34515|34516|34517|34518|34519|34520|34521|34522|34523|34524)" $<TARGET_FILE:rimu-colour> report F5)
rimu_cli_test("rimu-colour F6 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(37785|37786|37787|37788|37789|37790|37791|37792|37793|37794) 0\\.(38815|38816|38817|38818|38819|38820|38821|38822|38823|38824)" $<TARGET_FILE:rimu-colour> report F6)
rimu_cli_test("rimu-colour F8 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(34575|34576|34577|34578|34579|34580|34581|34582|34583|34584) 0\\.(35855|35856|35857|35858|35859|35860|35861|35862|35863|35864)" $<TARGET_FILE:rimu-colour> report F8)
rimu_cli_test("rimu-colour F9 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(37405|37406|37407|37408|37409|37410|37411|37412|37413|37414) 0\\.(37265|37266|37267|37268|37269|37270|37271|37272|37273|37274)" $<TARGET_FILE:rimu-colour> report F9)
rimu_cli_test("rimu-colour F10 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(34575|34576|34577|34578|34579|34580|34581|34582|34583|34584) 0\\.(35875|35876|35877|35878|35879|35880|35881|35882|35883|35884)" $<TARGET_FILE:rimu-colour> report F10)
rimu_cli_test("rimu-colour F12 native matches CIE 15 Table T.8" 0
              "xy  \\(2°\\) +0\\.(43695|43696|43697|43698|43699|43700|43701|43702|43703|43704) 0\\.(40415|40416|40417|40418|40419|40420|40421|40422|40423|40424)" $<TARGET_FILE:rimu-colour> report F12)

# Spectral values at the edges of double precision through every rimu-colour and rimu-light subcommand: exit 0 or 1,
# never NaN or Inf in any output; values outside 0 or 1e-30 to 1e30 refused with the reason and line.
add_test(NAME "cli: extreme spectral values never print NaN or Inf"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/extreme_spectra.sh $<TARGET_FILE:rimu-colour> $<TARGET_FILE:rimu-light>)
