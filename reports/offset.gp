# offset.gp -- report part `offset`: what the centric formulas cost on an offset engine, and what the offset buys.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/offset.gp
#
# Reads  in_dir/offset.csv and in_dir/offset_thrust.csv (columns by their header names, validation/src/parts/offset.cc)
# Writes out_dir/offset.svg and out_dir/offset.png
#
# Left: the centric forms' largest error over the cycle against delta / r, one line per quantity (x_p, a_p,
# wall_force, drive_torque; log y, 0 drawn at 1e-17), with the offset engine's own |analytic - Simbody| as dots.
# Right: the peak side thrust on the major (N_w > 0) and minor side against delta / r, analytic lines, Simbody dots.
# Each series' rows come together, in order of delta / r (crankcheck sorts the tables by their first column).

# The reference engine drawn beside the closed forms: crankcheck passes the first one in play (an engine that sat out
# is not drawn); alone, Simbody.
if (!exists("reference")) reference = "simbody"
if (!exists("reference_title")) reference_title = "Simbody"

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "offset"
cost = in_dir . "/offset.csv"
thrust = in_dir . "/offset_thrust.csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
nlines = 0
stats cost using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . cost . " is missing or empty (not even a header line)"; exit status 1 }
nlines = 0
stats thrust using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . thrust . " is missing or empty (not even a header line)"; exit status 1 }
set datafile columnheaders

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
array Q[4] = ["x_p", "a_p", "wall_force", "drive_torque"]
array C[4] = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728"]
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1100,520 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 1100,520 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 1100,520 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    set multiplot layout 1,2 title "Pin offset (desaxe): the centric forms' error, and the side thrust" font ",13"
    set grid lc rgb "#dddddd"
    set key bottom right font ",9" samplen 2
    set xlabel "pin offset delta / r (negative: toward the major-thrust side)"
    set logscale y
    set format y "10^{%T}"
    set ylabel "largest error over the cycle / scale"
    set yrange [floor / 3 : 10]
    plot for [i = 1:4] cost using "offset_over_r [-]":(strcol("quantity") eq Q[i] ? clamp(column("max_rel_error [-]")) : NaN) with linespoints lw 2 pt 7 ps 0.6 lc rgb C[i] title Q[i] . " (centric form)" noenhanced, \
         for [i = 1:4] cost using "offset_over_r [-]":(strcol("quantity") eq Q[i] ? clamp(column(reference . "_max_rel_error [-]")) : NaN) with points pt 6 ps 0.8 lc rgb C[i] notitle, \
         NaN with points pt 6 lc rgb "#444444" title "analytic vs " . reference_title . " (offset engine)"
    unset logscale y
    set format y "%g"
    set yrange [*:*]
    set ylabel "peak side thrust [N]"
    plot thrust using "offset_over_r [-]":(strcol("engine") eq "analytic" ? column("peak_major_thrust [N]") : NaN) with lines lw 2 lc rgb "#d62728" title "major side (N_w > 0)" noenhanced, \
         thrust using "offset_over_r [-]":(strcol("engine") eq "analytic" ? column("peak_minor_thrust [N]") : NaN) with lines lw 2 lc rgb "#1f77b4" title "minor side", \
         thrust using "offset_over_r [-]":(strcol("engine") eq reference ? column("peak_major_thrust [N]") : NaN) with points pt 7 ps 0.6 lc rgb "#d62728" title reference_title, \
         thrust using "offset_over_r [-]":(strcol("engine") eq reference ? column("peak_minor_thrust [N]") : NaN) with points pt 7 ps 0.6 lc rgb "#1f77b4" notitle
    unset multiplot
    unset output
}
