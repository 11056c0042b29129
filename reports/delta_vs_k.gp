# delta_vs_k.gp -- speed fluctuation of the free run due to gravity, against the number of cylinders k.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/delta_vs_k.gp
#
# Reads  in_dir/delta_vs_k.csv (validation/src/parts/delta_vs_k.cc declares its columns), each column by its header
#        ("speed_rpm [rpm]")
# Writes out_dir/delta_vs_k.svg and out_dir/delta_vs_k.png
#
# Two panels side by side (two-stroke left, four-stroke right), same log y axis. Per speed_rpm, one
# solid line with filled points: delta_due_to_gravity = |delta_gravity - delta_no_gravity| against
# k = 1..12, and one thin dashed line without points: delta_no_gravity (the fluctuation from the
# varying reduced inertia J(phi) alone). Colours run from dark violet (slowest speed) to orange
# (fastest), by rank of the speed. delta_gravity is not drawn. Zeros (and anything below 1e-17) are
# drawn at 1e-17. k = 7, 9, 11 are shaded. Rows may come in any order; an absent cycle, speed or
# column simply has no line, and an absent cycle leaves its panel empty with a note.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "delta_vs_k"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
fin(v) = (v == v && abs(v) < 1e300)      # false for nan and inf: such values are not drawn

# ---- number of data rows: a constant-only "using" counts the header line too (no warning even for a
#      header-only CSV); every later stats is skipped when there is no data row ----------------------
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
# The count above includes the header line; from here on it names the columns (until the series are drawn from the
# datablocks below, which have none).
set datafile columnheaders

# ---- presence per (cycle, speed, series), the distinct speeds and the range of the plotted values ---
# All numbers are read with column(): for an empty last field gnuplot 5.4's strcol returns a stale
# string, column() returns NaN (an empty delta_due_to_gravity is simply not drawn).
# The two series: "no_gravity" (dashed) and "due_to_gravity" (solid), each the column "delta_SERIES [-]".
present = "|"; cycles = "|"; speeds = " "; ymin = 1; ymax = 1e-17
spd(v) = sprintf("%.17g", v)
delta(col) = column("delta_" . col . " [-]")
row_ok(col) = fin(column("k [-]")) && fin(column("speed_rpm [rpm]")) && fin(delta(col))
reg(c, s, col) = (strstrt(present, "|" . c . ":" . s . ":" . col . "|") == 0) ? present = present . c . ":" . s . ":" . col . "|" : 0
if (ndata > 0) {
    stats file using ( \
        c = strcol("cycle"), v = column("speed_rpm [rpm]"), \
        (row_ok("no_gravity") || row_ok("due_to_gravity")) && strstrt(cycles, "|" . c . "|") == 0 ? cycles = cycles . c . "|" : 0, \
        (row_ok("no_gravity") || row_ok("due_to_gravity")) && strstrt(speeds, " " . spd(v) . " ") == 0 ? speeds = speeds . spd(v) . " " : 0, \
        row_ok("no_gravity") ? reg(c, spd(v), "no_gravity") : 0, \
        row_ok("due_to_gravity") ? reg(c, spd(v), "due_to_gravity") : 0, \
        row_ok("no_gravity") ? (y = delta("no_gravity"), ymin = clamp(y) < ymin ? clamp(y) : ymin, ymax = y > ymax ? y : ymax) : 0, \
        row_ok("due_to_gravity") ? (y = delta("due_to_gravity"), ymin = clamp(y) < ymin ? clamp(y) : ymin, ymax = y > ymax ? y : ymax) : 0, \
        0) nooutput
}

has(c, s, col) = strstrt(present, "|" . c . ":" . s . ":" . col . "|") > 0
hascycle(c) = strstrt(cycles, "|" . c . "|") > 0

# ---- the distinct speeds, sorted (selection sort), and their colours ----------------------------
NS = words(speeds)
array SPV[NS > 0 ? NS : 1]
array SPS[NS > 0 ? NS : 1]
array SPC[NS > 0 ? NS : 1]
do for [i = 1:NS] { SPV[i] = real(word(speeds, i)) }
do for [i = 1:NS] {
    m = i
    do for [j = i + 1:NS] { if (SPV[j] < SPV[m]) { m = j } }
    t = SPV[i]; SPV[i] = SPV[m]; SPV[m] = t
}
do for [i = 1:NS] { SPS[i] = spd(SPV[i]) }
# colour ramp by rank, dark violet (slowest) to orange (fastest); the stops are those of the Fourier
# orders in error_vs_lambda.gp
array RR[6] = [13, 83, 139, 184, 219, 244]
array GG[6] = [8, 2, 10, 50, 92, 136]
array BB[6] = [135, 163, 165, 137, 104, 73]
do for [i = 1:NS] {
    t = (NS > 1) ? 5.0 * (i - 1) / (NS - 1) : 0.0
    s = int(t); s = (s > 4) ? 4 : s; f = t - s
    SPC[i] = sprintf("#%02x%02x%02x", int(RR[s+1] + f * (RR[s+2] - RR[s+1]) + 0.5), \
                     int(GG[s+1] + f * (GG[s+2] - GG[s+1]) + 0.5), int(BB[s+1] + f * (BB[s+2] - BB[s+1]) + 0.5))
}

# ---- one comma-separated datablock per present series (robust to any row order) ------------------
array CYC[2] = ["two-stroke", "four-stroke"]
array CMD[2]
nser = 0
do for [p = 1:2] {
    CMD[p] = ""
    do for [i = 1:NS] {
        # dashed first, so the solid line of the same speed is drawn on top of it
        do for [col in "no_gravity due_to_gravity"] {
            if (has(CYC[p], SPS[i], col)) {
                nser = nser + 1
                eval sprintf("set table $S%d separator comma", nser)
                plot file using "k [-]":(clamp(delta(col))) with table \
                    if (strcol("cycle") eq CYC[p] && row_ok(col) && column("speed_rpm [rpm]") == SPV[i])
                unset table
                if (col eq "due_to_gravity") {
                    CMD[p] = CMD[p] . sprintf("$S%d using 1:2 smooth unique with linespoints lw 2 pt 7 ps 0.8 lc rgb '%s' notitle, ", nser, SPC[i])
                } else {
                    CMD[p] = CMD[p] . sprintf("$S%d using 1:2 smooth unique with lines lw 1.2 dt 2 lc rgb '%s' notitle, ", nser, SPC[i])
                }
            }
        }
    }
    CMD[p] = (CMD[p] eq "") ? "NaN notitle" : CMD[p][1:strlen(CMD[p]) - 2]
}
unset datafile columnheaders

# the legend (NaN plots, drawn in a panel of its own): one entry per speed, then the two line kinds
legend = ""
do for [i = 1:NS] {
    legend = legend . sprintf("NaN with linespoints lw 2 pt 7 ps 0.8 lc rgb '%s' title '%s rpm', ", SPC[i], sprintf("%g", SPV[i]))
}
legend = legend . "NaN with linespoints lw 2 pt 7 ps 0.8 lc rgb '#444444' title 'solid: δ due to gravity', " . \
                  "NaN with lines lw 1.2 dt 2 lc rgb '#444444' title 'dashed: δ without gravity'"

# ---- axes (after every stats: stats obeys the ranges) --------------------------------------------
set logscale y
nodata = (present eq "|")
if (nodata) { ymin = 1e-5; ymax = 1 }                 # no data at all: an arbitrary empty axis
lo = 10**floor(log10(ymin) + 1e-9); hi = 10**(ceil(log10(ymax) - 1e-9) + 1)
if (lo <= floor) { lo = floor / 3 }                    # room below the points drawn at 1e-17
if (hi < lo * 1000) { hi = lo * 1000 }                # at least three decades
set xrange [0.5:12.5]
set yrange [lo : hi]
set xtics 1, 1, 12
set format y "10^{%T}"
ystep = (hi / lo > 1e9) ? 100 : 10
ystart = (ystep == 100) ? 1e-16 : 1e-17
set ytics ystart, ystep
set grid ytics lc rgb "#dddddd"
set xlabel "number of cylinders k" font ",10"
set border; set tics
set style textbox opaque noborder margins 2, 2

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
    set multiplot title "Speed fluctuation due to gravity in the free run, against k (dashed: inertia alone)" font ",12"
    # the shading is set here, not once: the legend panel below unsets it
    do for [k in "7 9 11"] {
        eval sprintf("set object %d rectangle from first %s - 0.4, graph 0 to first %s + 0.4, graph 1 fillcolor rgb '#fff2b3' fillstyle solid 1.0 noborder behind", k + 0, k, k)
    }
    set border; set tics; set xtics 1, 1, 12; set ytics ystart, ystep; set grid ytics lc rgb "#dddddd"
    set xlabel "number of cylinders k" font ",10"
    set tmargin at screen 0.86
    set bmargin at screen 0.31
    unset key

    do for [p = 1:2] {
        c = CYC[p]
        set title (c) font ",11" offset 0, -0.3
        if (p == 1) {
            set ylabel "coefficient of speed fluctuation δ (log scale)" font ",10"
            set lmargin at screen 0.085
            set rmargin at screen 0.49
        } else {
            set ylabel ""
            set lmargin at screen 0.565
            set rmargin at screen 0.97
        }
        unset label 5
        if (!hascycle(c)) { set label 5 "no " . c . " rows in the CSV" at graph 0.5, graph 0.5 center front boxed }
        eval "plot " . CMD[p]
    }

    # the legend and the notes: an empty panel as wide as the figure (a key is laid out within the
    # width of its own panel, too narrow in either data panel for a horizontal legend)
    unset label 5
    unset object 7; unset object 9; unset object 11
    unset title; unset xlabel; unset ylabel; unset border; unset tics; unset grid
    set lmargin at screen 0.02
    set rmargin at screen 0.98
    set tmargin at screen 0.20
    set bmargin at screen 0.02
    set key at screen 0.5, screen 0.155 center center horizontal maxrows 2 reverse Left samplen 3 font ",9" width 1 box lc rgb "#bbbbbb"
    set label 8 "shaded: k = 7, 9, 11 (the paper: gravity negligible, first surviving order 2k)" at screen 0.5, screen 0.075 center font ",9" tc rgb "#555555"
    if (ymin <= floor) { set label 9 "0 shown at 10^{-17} (below double precision)" at screen 0.5, screen 0.035 center font ",9" tc rgb "#444444" }
    eval "plot " . legend
    unset label 8
    unset label 9
    unset multiplot
    unset output
}
