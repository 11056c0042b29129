# gravity_significance.gp -- how large the gravity torque is, against the number of cylinders k.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/gravity_significance.gp
#
# Reads  in_dir/gravity_significance.csv (columns by their header names, validation/src/parts/gravity_significance.cc;
#        the first reference engine's ENGINE_ratio_to_k1 and ENGINE_resolved drawn, optional)
# Writes out_dir/gravity_significance.svg and out_dir/gravity_significance.png
#
# Per cycle (two-stroke blue, four-stroke orange) two lines against k = 1..12 on a log y axis:
# ratio_to_k1 (solid, filled points) = max|Q| relative to the same cycle's k = 1, and
# ratio_to_inertia (dashed, open points) = max|Q| relative to the largest inertia torque.
# The first reference engine's max |Q| relative to its k = 1 (ENGINE_ratio_to_k1) is drawn as a cross where it
# resolves it (ENGINE_resolved "yes") and as an arrow down from its rounding bound where it does not ("no"): an upper bound,
# not a value. Values below 1e-17 are drawn at 1e-17. k = 7, 9, 11 are shaded. Rows may come in any
# order; an absent cycle or column simply has no line.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "gravity_significance"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
fin(v) = (v == v && abs(v) < 1e300)      # false for nan and inf: such values are not drawn

# ---- presence per (cycle, column) and the range of the plotted values ----------------------------
present = "|"; ymin = 1; ymax = 1
reg(c, col, v) = (fin(v) && strstrt(present, "|" . c . ":" . col . "|") == 0) ? present = present . c . ":" . col . "|" : 0
# ---- number of data rows: a constant-only "using" counts the header line too (no warning even for a
#      header-only CSV); every later stats is skipped when there is no data row ----------------------
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
set datafile columnheaders
K = "k [-]"; TO_K1 = "ratio_to_k1 [-]"; TO_INERTIA = "ratio_to_inertia [-]"

if (ndata > 0) {
    stats file using (reg(strcol("cycle"), TO_K1, column(TO_K1)), reg(strcol("cycle"), TO_INERTIA, column(TO_INERTIA)), \
        (fin(column(TO_K1)) ? (ymin = clamp(column(TO_K1)) < ymin ? clamp(column(TO_K1)) : ymin, \
                                   ymax = column(TO_K1) > ymax ? column(TO_K1) : ymax) : 0), \
        (fin(column(TO_INERTIA)) ? (ymin = clamp(column(TO_INERTIA)) < ymin ? clamp(column(TO_INERTIA)) : ymin, \
                                   ymax = column(TO_INERTIA) > ymax ? column(TO_INERTIA) : ymax) : 0), 0) nooutput
}

has(c, col) = strstrt(present, "|" . c . ":" . col . "|") > 0

array CYC[2] = ["two-stroke", "four-stroke"]
array COL[2] = [TO_K1, TO_INERTIA]
array WHAT[2] = ["relative to k = 1", "relative to the inertia torque"]
set style line 1 lc rgb "#1f77b4" lw 2 pt 7 ps 1.0
set style line 2 lc rgb "#1f77b4" lw 2 dt 2 pt 6 ps 1.1
set style line 3 lc rgb "#ff7f0e" lw 2 pt 5 ps 1.0
set style line 4 lc rgb "#ff7f0e" lw 2 dt 2 pt 4 ps 1.1

cmd = ""
do for [p = 1:2] {
    do for [w = 1:2] {
        if (has(CYC[p], COL[w])) {
            s = 2 * (p - 1) + w
            eval sprintf("set table $S%d separator comma", s)
            plot file using K:(clamp(column(COL[w]))) with table if (strcol("cycle") eq CYC[p] && fin(column(COL[w])))
            unset table
            cmd = cmd . sprintf("$S%d using 1:2 smooth unique with linespoints ls %d title '%s, %s', ", s, s, CYC[p], WHAT[w])
        }
    }
}
# The first reference engine: resolved values as crosses, bounds as arrows down (one decade long) ending in a down triangle.
# Its columns: the first header ending in "_ratio_to_k1 [-]" other than the closed forms' own.
REF = ""
suffix = "_" . TO_K1
isref(h) = (REF eq "" && strlen(h) > strlen(suffix) && h[strlen(h) - strlen(suffix) + 1:] eq suffix) ? (REF = h, 1) : 0
if (ndata > 0) { stats file every ::0::0 using (sum [i = 1:100] isref(columnhead(i)), 1) nooutput }
RES = (REF eq "") ? "" : REF[1:strlen(REF) - strlen(suffix)] . "_resolved"
has12 = 0
if (REF ne "") { stats file using (has12 = (has12 || fin(column(REF))), 0) nooutput }
if (has12) {
    do for [p = 1:2] {
        eval sprintf("set table $R%d separator comma", p)
        plot file using K:(clamp(column(REF))) with table if (strcol("cycle") eq CYC[p] && strcol(RES) eq "yes" && fin(column(REF)))
        unset table
        eval sprintf("set table $B%d separator comma", p)
        plot file using K:(clamp(column(REF))) with table if (strcol("cycle") eq CYC[p] && strcol(RES) ne "yes" && fin(column(REF)))
        unset table
        eval sprintf("nr = |$R%d|; nb = |$B%d|", p, p)
        if (nr > 0) { cmd = cmd . sprintf("$R%d using 1:2 with points pt 2 ps 1.8 lw 2 lc rgb '%s' title 'reference engine, %s (resolved)', ", p, (p == 1 ? "#0b3d91" : "#a34a00"), CYC[p]) }
        if (nb > 0) {
            cmd = cmd . sprintf("$B%d using 1:2:(0):($2 * 0.1 - $2) with vectors head filled size screen 0.008,25 lw 1.5 lc rgb '%s' title 'reference engine, %s: below rounding (upper bound)', ", p, (p == 1 ? "#0b3d91" : "#a34a00"), CYC[p])
        }
    }
}
cmd = (cmd eq "") ? "NaN notitle" : cmd[1:strlen(cmd) - 2]
set datafile nocolumnheaders  # the datablocks made above have none

# ---- axes ---------------------------------------------------------------------------------------
set logscale y
lo = 10**floor(log10(ymin)); hi = 10**(ceil(log10(ymax)) + 1)
set xrange [0.5:12.5]
set yrange [lo : hi]
set xtics 1, 1, 12
set format y "10^{%T}"
ystep = (hi / lo > 1e9) ? 100 : 10
set ytics ystep
set grid ytics lc rgb "#dddddd"
set xlabel "number of cylinders k (inline, evenly spaced cranks)"
set ylabel "max |Q| ratio (dimensionless, log scale)"
do for [k in "7 9 11"] {
    set object rectangle from first k - 0.4, graph 0 to first k + 0.4, graph 1 fillcolor rgb "#fff2b3" fillstyle solid 1.0 noborder behind
}
set label 1 "shaded: k = 7, 9, 11 (the paper: gravity negligible, first surviving order 2k)" at graph 0.99, graph 0.97 right font ",9" tc rgb "#555555"
if (ymin <= floor) { set label 2 "values below 10^{-17} drawn at 10^{-17}" at graph 0.01, first floor left offset 0, 0.6 font ",9" tc rgb "#444444" }
set bmargin at screen 0.27
set key at screen 0.5, screen 0.085 center center horizontal maxcols 2 maxrows 4 width -8 reverse Left samplen 3 font ",9" box lc rgb "#bbbbbb"

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
    set title "How much gravity matters: max |Q| against k, relative to k = 1 and to the inertia torque" font ",12"
    eval "plot " . cmd
    unset output
}
