# rod_models.gp -- what the two-mass rod costs: its drive-torque error against Simbody's rigid rod.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/rod_models.gp
#
# Reads  in_dir/rod_models.csv (columns by their header names, validation/src/parts/rod_models.cc)
# Writes out_dir/rod_models.svg and out_dir/rod_models.png
#
# Two panels: the largest drive-torque error over the turn relative to the torque scale, against lambda (left,
# variable "lambda") and against Delta_I / I_G (right, variable "delta_I_over_I_G"), for engines "car" and "marine":
# the two-mass rod without Delta_I (solid) and the paper's two-mass rod with Delta_I (dashed). Errors of 0 or below
# 1e-17 are drawn at 1e-17. Rows may come in any order; missing series are left out.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "rod_models"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
set datafile columnheaders
clamp(v) = (v == v) ? ((v < 1e-17) ? 1e-17 : v) : NaN
set datafile missing NaN

array VAR[2] = ["lambda", "delta_I_over_I_G"]
array XLABEL[2] = ["crank ratio λ = r / l", "Δ_I / I_G  (I_G changed; 0: the two-mass ideal)"]
array ENG[2] = ["car", "marine"]
array COLOUR[2] = ["#1f77b4", "#d62728"]
sel(v, e, c) = (strcol("variable") eq VAR[v] && strcol("engine") eq ENG[e]) ? clamp(column(c)) : NaN

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 900,560 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 900,560 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 900,560 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    set multiplot title "The two-mass rod against Simbody's rigid rod: largest drive-torque error / torque scale" font ",12"
    set logscale y
    set yrange [1e-17:1]
    set format y "10^{%L}"
    set tmargin at screen 0.86
    set bmargin at screen 0.2
    set key at screen 0.5, screen 0.05 center center horizontal samplen 2 font ",9"
    do for [v = 1:2] {
        set lmargin at screen (v == 1 ? 0.09 : 0.57)
        set rmargin at screen (v == 1 ? 0.47 : 0.95)
        set xlabel XLABEL[v] font ",10"
        set ylabel (v == 1 ? "max |error| / torque scale" : "") font ",10"
        if (v == 1) {
            plot for [e = 1:2] file using "x [SI]":(sel(v, e, "two_mass_error [-]")) with linespoints pt 7 ps 0.6 lw 1.5 lc rgb COLOUR[e] title ENG[e] . ": two-mass rod", \
                 for [e = 1:2] file using "x [SI]":(sel(v, e, "two_mass_delta_I_error [-]")) with linespoints pt 6 ps 0.6 lw 1.5 dt 2 lc rgb COLOUR[e] title ENG[e] . ": with Δ_I (exact)"
        } else {
            plot for [e = 1:2] file using "x [SI]":(sel(v, e, "two_mass_error [-]")) with linespoints pt 7 ps 0.6 lw 1.5 lc rgb COLOUR[e] notitle, \
                 for [e = 1:2] file using "x [SI]":(sel(v, e, "two_mass_delta_I_error [-]")) with linespoints pt 6 ps 0.6 lw 1.5 dt 2 lc rgb COLOUR[e] notitle
        }
    }
    unset multiplot
    unset output
}
