# free_run_error_vs_time.gp -- a graded program's time-stepped run against the exact run (crankcheck grade --free-run).
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'; runs='CASE1 CASE2'" reports/free_run_error_vs_time.gp
#
# Reads  in_dir/free_run_history.csv   (validation/free_run_grade.h: RunHistoryRow), its columns by header name
# Writes out_dir/free_run_error_vs_time.svg and out_dir/free_run_error_vs_time.png
#
# Top: |phi_run - phi_exact| [rad] against time, one line per run (case: scene, drive and step). Bottom: the energy's
# error (E - E_0) / E_0 at each crossing of phi0 + 2 pi k, against time (free runs; energy=0 leaves it out). Errors of 0 are drawn at 1e-17.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
if (!exists("runs")) runs = ""
if (!exists("energy")) energy = 1   # 0: no free run, no energy panel
name = "free_run_error_vs_time"
file = in_dir . "/free_run_history.csv"

reset
set encoding utf8
set datafile separator ","
set datafile columnheaders
floor = 1e-17
clamp(v) = (abs(v) < floor) ? floor : abs(v)

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 900,700 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 900,700 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 900,700 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    if (energy) { set multiplot layout 2,1 } else { set multiplot layout 1,1 }
    set logscale y
    set format y "10^{%L}"
    set grid
    set key outside right top
    set xlabel "time [s]"
    set ylabel "|phase error| [rad]"
    plot for [r in runs] file using "time [s]":(strcol("case") eq r ? clamp(column("phase_error [rad]")) : NaN) \
         with lines lw 2 title r noenhanced
    set ylabel "|E - E_0| / E_0 at phi_0 + 2 pi k"
    if (energy) {
        plot for [r in runs] file using "time [s]":(strcol("case") eq r && strcol("energy_error [-]") ne "" ? \
             clamp(column("energy_error [-]")) : NaN) with linespoints lw 2 pt 7 ps 0.6 title r noenhanced
    }
    unset multiplot
    unset output
}
