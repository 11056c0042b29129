# speed_vs_error.gp -- cost per evaluation against error, one labelled point per method.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/speed_vs_error.gp
#
# Reads  in_dir/speed_vs_error.csv   its columns by their headers (below: method, ns_per_eval, max_rel_error)
# Writes out_dir/speed_vs_error.svg and out_dir/speed_vs_error.png
#
# x = ns per evaluation (log), y = max relative error (log; 0 or anything below 1e-17 is drawn at
# 1e-17). Every point is labelled with its method name and coloured by family (prefix of the name:
# exact*, fourier*, paper*, norton*, simbody*). The Pareto front -- the points that no other point
# beats on both cost and error -- is joined by a line, in order of cost. Rows may come in any
# order; rows whose ns_per_eval is not a positive number are ignored.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "speed_vs_error"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
ok(x, y) = (x > 0 && x < 1e300 && y == y && abs(y) < 1e300)   # finite, positive cost

# ---- read the rows into arrays ------------------------------------------------------------------
# number of data rows: a constant-only "using" counts the header line too (no warning even for a
# header-only CSV); every later stats is skipped when there is no data row
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
nrow = ndata
array MN[nrow > 0 ? nrow : 1]
array MX[nrow > 0 ? nrow : 1]
array MY[nrow > 0 ? nrow : 1]
n = 0
# the columns by their headers ("name [unit]"), the CSV's first line; the header mode only while the CSV is read (the
# datablocks made below have no header line)
c_method = "method"; c_ns = "ns_per_eval [ns]"; c_rel = "max_rel_error [-]"
set datafile columnheaders
if (nrow > 0) {
    stats file using (ok(column(c_ns), column(c_rel)) ? \
        (n = n + 1, MN[n] = strcol(c_method), MX[n] = column(c_ns), MY[n] = clamp(column(c_rel))) : 0, 0) nooutput
}
unset datafile columnheaders

# ---- Pareto front: not dominated (no other point at most as costly and at most as wrong, and
#      strictly better in one of the two), printed in increasing cost ------------------------------
array FR[n > 0 ? n : 1]
nfront = 0
do for [i = 1:n] {
    dom = 0
    do for [j = 1:n] {
        if (j != i && MX[j] <= MX[i] && MY[j] <= MY[i] && (MX[j] < MX[i] || MY[j] < MY[i])) { dom = 1 }
    }
    FR[i] = dom ? 0 : 1
    nfront = nfront + FR[i]
}
set print $front
do for [s = 1:nfront] {
    best = 0
    do for [i = 1:n] {
        if (FR[i] == 1 && (best == 0 || MX[i] < MX[best] || (MX[i] == MX[best] && MY[i] > MY[best]))) { best = i }
    }
    print sprintf("%.17g,%.17g", MX[best], MY[best])
    FR[best] = 2
}
unset print

xmin = 1.0; xmax = 10.0
do for [i = 1:n] {
    if (i == 1 || MX[i] < xmin) { xmin = MX[i] }
    if (i == 1 || MX[i] > xmax) { xmax = MX[i] }
}

# ---- family colours -----------------------------------------------------------------------------
set linetype 11 lc rgb "#000000"
set linetype 12 lc rgb "#7b2cbf"
set linetype 13 lc rgb "#8c564b"
set linetype 14 lc rgb "#1f77b4"
set linetype 15 lc rgb "#2ca02c"
set linetype 16 lc rgb "#7f7f7f"
starts(s, p) = (strlen(s) >= strlen(p) && s[1:strlen(p)] eq p)
family(s) = starts(s, "exact") ? 11 : starts(s, "fourier") ? 12 : starts(s, "paper") ? 13 : \
            starts(s, "norton") ? 14 : starts(s, "simbody") ? 15 : 16

# ---- axes ---------------------------------------------------------------------------------------
set logscale xy
# room on the right for the labels, which are written to the right of their points
set xrange [xmin / 2 : xmax * 12]
if (n > 0) { set yrange [floor / 3 : 1<*] } else { set yrange [floor / 3 : 1] }
set format x "10^{%T}"
set format y "10^{%T}"
set ytics 1e-16, 100
set grid xtics ytics mxtics lc rgb "#dddddd" lw 1
set xlabel "cost per evaluation (ns, log scale)"
set ylabel "max relative error (dimensionless)"
set label 9 "0 shown at 10^{-17} (below double precision)" at graph 0.99, first floor right offset 0, 0.6 font ",9" tc rgb "#444444"
set arrow 1 from graph 0, first floor to graph 1, first floor nohead dt 3 lc rgb "#999999" back
set key below horizontal reverse Left samplen 2 font ",10" box lc rgb "#bbbbbb"
set bmargin 6

if (n == 0) { set label 8 "no data rows in " . name . ".csv" at graph 0.5, graph 0.5 center noenhanced; unset key }

# Legend: one NaN plot per family present in the data. Drawing order: front line, then the labels
# on an opaque white box (so the line does not run through a name), then the points on top.
set style textbox opaque noborder margins 1, 1
array FAM[6] = ["exact closed form", "Fourier series", "paper as printed", "Norton two-term", "Simbody", "other"]
array FAMN[6] = [0, 0, 0, 0, 0, 0]
do for [i = 1:n] { FAMN[family(MN[i]) - 10] = 1 }
# the valid rows once more, as a datablock: cost, clamped error, name, family colour
set print $pts
do for [i = 1:n] { print sprintf("%.17g,%.17g,%s,%d", MX[i], MY[i], MN[i], family(MN[i])) }
unset print
plotcmd = ""
if (n > 0) {
  plotcmd = "$front using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' title 'Pareto front', " . \
  "$pts using 1:2:3 with labels left offset 0.9, 0.35 boxed font ',9' noenhanced notitle, " . \
  "$pts using 1:2:4 with points pt 7 ps 1.3 lc variable notitle"
  do for [f = 1:6] {
    if (FAMN[f]) { plotcmd = plotcmd . sprintf(", NaN with points pt 7 ps 1.3 lt %d title '%s'", 10 + f, FAM[f]) }
  }
} else {
  plotcmd = "NaN notitle"
}

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
    set title "Cost per evaluation against error (Pareto front joined)" font ",13"
    eval "plot " . plotcmd
    unset output
}
