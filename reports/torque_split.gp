# torque_split.gp -- the drive torque of a running engine and its gas, inertia and gravity parts; gravity's share.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/torque_split.gp
#
# Reads  in_dir/torque_split.csv and in_dir/gravity_share.csv (columns by their header names,
#        validation/src/parts/torque_split.cc)
# Writes out_dir/torque_split.svg and out_dir/torque_split.png
#
# Left and middle: the drive torque over one working cycle of the car inline four (engine "car_inline4_6000rpm") and
# of the marine two-stroke ("marine_inline6_two_stroke"), with its parts (analytic) and Simbody's whole drive torque
# as dots. Right: gravity's share of the mean absolute drive torque against k, one line per speed and stroke (log
# axis; rows with resolved = 0, gravity torques below double precision, are left out). Rows may come in any order;
# an engine or stroke without rows leaves its panel or line out.

# The reference engine drawn beside the closed forms: crankcheck passes the first one in play (an engine that sat out
# is not drawn); alone, Simbody.
if (!exists("reference")) reference = "simbody"
if (!exists("reference_title")) reference_title = "Simbody"

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "torque_split"
file = in_dir . "/" . name . ".csv"
share = in_dir . "/gravity_share.csv"

reset
set encoding utf8
set datafile separator ","
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
nshare = 0
stats share using (nshare = nshare + 1, 1) nooutput
if (nshare == 0) { print "error: " . share . " is missing or empty (not even a header line)"; exit status 1 }
set datafile columnheaders
PHI = "phi_deg [deg]"

array ENG[2] = ["car_inline4_6000rpm", "marine_inline6_two_stroke"]
array TITLE[2] = ["car inline four, four-stroke, 6000 rpm", "marine inline six, two-stroke, 105 rpm"]
array N[2]
do for [e = 1:2] {
    N[e] = 0
    if (nlines > 1) { stats file using (strcol("engine") eq ENG[e] ? N[e] = N[e] + 1 : 0, 0) nooutput }
}
sel(e, c) = (strcol("engine") eq ENG[e]) ? column(c) : NaN
pos(x) = (x > 0 && x == x) ? x : NaN

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
    set multiplot title "The drive torque of a running engine: gas, inertia and gravity (" . reference_title . "'s whole as dots)" font ",12"
    set tmargin at screen 0.86
    set bmargin at screen 0.22
    do for [e = 1:2] {
        set lmargin at screen (e == 1 ? 0.07 : 0.38)
        set rmargin at screen (e == 1 ? 0.33 : 0.64)
        set title TITLE[e] font ",10"
        set xlabel "crank angle φ [deg]" font ",9"
        set ylabel (e == 1 ? "torque the shaft must receive [N m]" : "") font ",9"
        set xrange [0:(e == 1 ? 720 : 360)]
        set xtics 0, (e == 1 ? 180 : 90) font ",8"
        set ytics autofreq font ",8"
        set format y "%.0s%c"
        set key at screen 0.36, screen 0.07 center center horizontal samplen 1.5 font ",9"
        unset label 5
        if (N[e] == 0) {
            set label 5 "no rows in the CSV" at graph 0.5, graph 0.5 center front
            set xrange [0:1]
            set yrange [0:1]
            plot NaN notitle
            set autoscale xy
        } else { if (e == 1) {
            plot file using PHI:(sel(e, "gas_torque [N m]")) smooth unique with lines lw 1.5 lc rgb "#d62728" title "gas", \
                 file using PHI:(sel(e, "inertia_torque [N m]")) smooth unique with lines lw 1.5 lc rgb "#1f77b4" title "inertia", \
                 file using PHI:(sel(e, "gravity_torque [N m]")) smooth unique with lines lw 2 lc rgb "#2ca02c" title "gravity", \
                 file using PHI:(sel(e, "drive_torque [N m]")) smooth unique with lines lw 2 lc rgb "black" title "drive torque (analytic)", \
                 file every 4 using PHI:(sel(e, reference . "_drive_torque [N m]")) with points pt 7 ps 0.35 lc rgb "#777777" title reference_title
        } else {
            unset key
            plot file using PHI:(sel(e, "gas_torque [N m]")) smooth unique with lines lw 1.5 lc rgb "#d62728" notitle, \
                 file using PHI:(sel(e, "inertia_torque [N m]")) smooth unique with lines lw 1.5 lc rgb "#1f77b4" notitle, \
                 file using PHI:(sel(e, "gravity_torque [N m]")) smooth unique with lines lw 2 lc rgb "#2ca02c" notitle, \
                 file using PHI:(sel(e, "drive_torque [N m]")) smooth unique with lines lw 2 lc rgb "black" notitle, \
                 file every 4 using PHI:(sel(e, reference . "_drive_torque [N m]")) with points pt 7 ps 0.35 lc rgb "#777777" notitle
        } }
    }
    set lmargin at screen 0.72
    set rmargin at screen 0.98
    set title "gravity's share of mean |drive torque|" font ",10"
    set xlabel "cylinders k" font ",9"
    set ylabel ""
    set logscale y
    set format y "10^{%L}"
    set datafile missing NaN  # rows of other speeds are skipped, the line goes on
    set xrange [0.5:12.5]
    set xtics 1, 1, 12 font ",8"
    set key at screen 0.85, screen 0.07 center center maxrows 4 samplen 1.2 font ",8"
    plot for [rpm in "600 6000"] share using "k [-]":((strcol("cycle") eq "four-stroke" && column("speed_rpm [rpm]") == rpm + 0 && column("resolved") == 1) ? pos(column("share [-]")) : NaN) \
             with linespoints pt 7 ps 0.5 lw 1.5 title "four-stroke " . rpm . " rpm", \
         for [rpm in "600 6000"] share using "k [-]":((strcol("cycle") eq "two-stroke" && column("speed_rpm [rpm]") == rpm + 0 && column("resolved") == 1) ? pos(column("share [-]")) : NaN) \
             with linespoints pt 6 ps 0.5 lw 1.5 dt 2 title "two-stroke " . rpm . " rpm"
    unset logscale y
    set datafile missing
    set format y "%g"
    set autoscale x
    unset multiplot
    unset output
}
