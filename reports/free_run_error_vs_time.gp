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
fin(v) = (v == v && abs(v) < 1e308)   # an empty cell reads as NaN

# One datablock per run and panel, its rows pulled out by their key column whatever the file's order (then sorted by
# time).
N = words(runs)
do for [i = 1:N] {
    eval sprintf("set table $P%d separator comma", i)
    plot file using (column("time [s]")):(clamp(column("phase_error [rad]"))) with table if (strcol("case") eq word(runs, i))
    unset table
    if (energy) {
        eval sprintf("set table $E%d separator comma", i)
        plot file using (column("time [s]")):(clamp(column("energy_error [-]"))) with table \
            if (strcol("case") eq word(runs, i) && fin(column("energy_error [-]")))
        unset table
    }
}
unset datafile columnheaders

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
    plot for [i = 1:N] sprintf("$P%d", i) using 1:2 smooth unique with lines lw 2 title word(runs, i) noenhanced
    set ylabel "|E - E_0| / E_0 at phi_0 + 2 pi k"
    if (energy) {
        plot for [i = 1:N] sprintf("$E%d", i) using 1:2 smooth unique with linespoints lw 2 pt 7 ps 0.6 \
             title word(runs, i) noenhanced
    }
    unset multiplot
    unset output
}
