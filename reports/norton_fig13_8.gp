# norton_fig13_8.gp -- piston position, velocity and acceleration over two revolutions, exact
# against Norton's two-term approximation (Design of Machinery, 13.3c-e), in the manner of his
# figure 13-8.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/norton_fig13_8.gp
#
# Reads  in_dir/norton_fig13_8.csv (validation/src/parts/norton_fig13_8.cc declares its columns), each column by its
#        header ("x_exact [m]")
# Writes out_dir/norton_fig13_8.svg and out_dir/norton_fig13_8.png
#
# Three stacked panels sharing the crank-angle axis (tics every 90 degrees). Exact: coloured solid
# line; two-term: black dashed line. Each panel states the largest |two-term - exact| over the rows.
# Rows are sorted by crank angle before drawing (smooth unique), so their order does not matter.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "norton_fig13_8"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","

# ---- largest difference per quantity, and the angle range ----------------------------------------
array D[3] = [0, 0, 0]
# Panel p's columns: EXACT[p] and TWO[p].
array EXACT[3] = ["x_exact [m]", "v_exact [m/s]", "a_exact [m/s^2]"]
array TWO[3] = ["x_two_term [m]", "v_two_term [m/s]", "a_two_term [m/s^2]"]
# number of data rows: a constant-only "using" counts the header line too (no warning even for a
# header-only CSV); every later stats is skipped when there is no data row
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
# The count above includes the header line; from here on it names the columns.
set datafile columnheaders
nrow = ndata
amin = 0; amax = 720
array YMIN[3] = [0.0, 0.0, 0.0]; array YMAX[3] = [1.0, 1.0, 1.0]
if (ndata > 0) {
    stats file using ( \
        (d = abs(column(TWO[1]) - column(EXACT[1])), d > D[1] ? D[1] = d : 0), \
        (d = abs(column(TWO[2]) - column(EXACT[2])), d > D[2] ? D[2] = d : 0), \
        (d = abs(column(TWO[3]) - column(EXACT[3])), d > D[3] ? D[3] = d : 0), \
        (a = column("crank_angle_deg [deg]"), a < amin ? amin = a : 0), (a > amax ? amax = a : 0), 0) nooutput
    # per panel the smallest and largest value over both columns, for a y range with headroom
    do for [p = 1:3] {
        YMIN[p] = 0; YMAX[p] = 0; first = 1
        stats file using (v = column(EXACT[p]), w = column(TWO[p]), \
            (v == v ? (first ? (YMIN[p] = v, YMAX[p] = v, first = 0) : 0, YMIN[p] = v < YMIN[p] ? v : YMIN[p], YMAX[p] = v > YMAX[p] ? v : YMAX[p]) : 0), \
            (w == w ? (first ? (YMIN[p] = w, YMAX[p] = w, first = 0) : 0, YMIN[p] = w < YMIN[p] ? w : YMIN[p], YMAX[p] = w > YMAX[p] ? w : YMAX[p]) : 0), 0) nooutput
    }
}
# a tic step of 1, 2 or 5 times a power of ten giving about four intervals
nice(x) = (m = 10**floor(log10(x)), f = x / m, (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * m)

array QN[3] = ["piston position x", "piston velocity v", "piston acceleration a"]
array QU[3] = ["m", "m/s", "m/s^2"]
array QL[3] = ["x (m)", "v (m/s)", "a (m/s^2)"]
array QC[3] = ["#1f77b4", "#2ca02c", "#d62728"]

set xrange [amin : amax]
set xtics amin, 90, amax
set mxtics 3
set grid xtics ytics lc rgb "#dddddd"
set ytics font ",9"
set format y "%g"
set lmargin at screen 0.10
set rmargin at screen 0.97
set key horizontal reverse Left samplen 4 font ",9" nobox

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
    set multiplot title "Piston motion against crank angle (after Norton fig. 13-8): exact solid, Norton's two-term form dashed" font ",12"
    do for [p = 1:3] {
        top = 0.885 - (p - 1) * 0.262
        set tmargin at screen top
        set bmargin at screen top - 0.235
        if (p < 3) { set format x ""; set xlabel "" } else { set format x "%g"; set xlabel "crank angle (degrees)" offset 0, 0.3 }
        set ylabel (QL[p]) offset 1, 0
        span = YMAX[p] - YMIN[p]
        if (!(span > 0)) { span = (abs(YMAX[p]) > 0 ? abs(YMAX[p]) : 1) }
        set yrange [YMIN[p] - 0.06 * span : YMAX[p] + 0.30 * span]
        set ytics nice(span / 4.0)
        if (p == 1) { set key at screen 0.97, screen 0.935 right top } else { unset key }
        set label 1 sprintf("%s;  max |two-term − exact| = %.2g %s", QN[p], D[p], QU[p]) at graph 0.01, graph 0.93 left font ",9" front textcolor rgb "#333333" boxed
        set style textbox opaque noborder
        if (nrow == 0) {
            set label 2 "no rows in the CSV" at graph 0.5, graph 0.5 center
            plot NaN notitle
        } else {
            plot file using "crank_angle_deg [deg]":(column(EXACT[p])) smooth unique with lines lw 4 lc rgb QC[p] title "exact", \
                 file using "crank_angle_deg [deg]":(column(TWO[p])) smooth unique with lines lw 1.5 dt (8, 6) lc rgb "black" title "two-term (13.3c-e)"
        }
    }
    unset multiplot
    unset output
}
