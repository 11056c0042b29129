# free_run_error_vs_step.gp -- a graded program's errors against its time step (crankcheck grade --free-run --dt-sweep).
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'; measures='energy_trend delta phase'; scene='NAME'" reports/free_run_error_vs_step.gp
#
# Reads  in_dir/free_run_measures.csv   (validation/free_run_grade.h: RunMeasureRow), its columns by header name
# Writes out_dir/free_run_error_vs_step.svg and out_dir/free_run_error_vs_step.png
#
# One line per measure of the scene's runs: the error divided by its tolerance, against the step dt (log-log): a point
# below 1 (dashed) meets the tolerance; the slope is the measure's observed order. Errors of 0 are drawn at 1e-17.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
if (!exists("measures")) measures = "energy_trend delta phase"
if (!exists("scene")) scene = ""
name = "free_run_error_vs_step"
file = in_dir . "/free_run_measures.csv"

reset
set encoding utf8
set datafile separator ","
set datafile columnheaders
floor = 1e-17
clamp(v) = (v < floor) ? floor : v

# One datablock per measure, its rows pulled out by their key columns whatever the file's order (then sorted by dt).
N = words(measures)
do for [i = 1:N] {
    eval sprintf("set table $M%d separator comma", i)
    plot file using (column("dt [s]")):(clamp(column("error [SI]") / column("tolerance [SI]"))) with table \
        if (strcol("scene") eq scene && strcol("measure") eq word(measures, i))
    unset table
}
unset datafile columnheaders

set logscale xy
set format y "10^{%L}"
set xlabel "time step dt [s]"
set ylabel "error / tolerance [-]"
set key outside right top
set grid

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 900,520 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 900,520 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 900,520 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    plot for [i = 1:N] sprintf("$M%d", i) using 1:2 smooth unique with linespoints lw 2 pt 7 \
             title word(measures, i) noenhanced, \
         1 with lines dt 2 lc rgb "gray40" title "tolerance"
    unset output
}
