# integrator_pareto.gp -- Simbody's integrators: cost per simulated revolution against error.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/integrator_pareto.gp
#
# Reads  in_dir/integrator_pareto.csv   its columns by their headers (below: integrator, accuracy, ns_per_revolution,
#                                       delta_error, energy_drift)
# Writes out_dir/integrator_pareto.svg and out_dir/integrator_pareto.png
#
# Two log-log panels side by side, same x axis: x = ns per simulated revolution; y = delta_error
# (left: relative error of the speed-fluctuation coefficient against the analytic value) and
# energy_drift (right: relative energy drift per revolution). One colour per integrator, its points
# joined in order of the accuracy setting (loosest first) and each labelled with that setting
# ("1e-6"). In each panel the Pareto front over all integrators -- the points that no other point
# beats on both cost and error -- is joined by a red dashed line, in order of cost. 0 or anything
# below 1e-17 is drawn at 1e-17. Rows may come in any order; rows whose ns_per_revolution or
# accuracy is not a positive finite number are ignored, and a nan/inf/empty error only drops the
# point from its panel.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "integrator_pareto"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
fin(v) = (v == v && abs(v) < 1e300)      # false for nan and inf: such values are not drawn
pos(v) = (v > 0 && v < 1e300)            # positive and finite

# ---- read the rows into arrays ------------------------------------------------------------------
# number of data rows: a constant-only "using" counts the header line too (no warning even for a
# header-only CSV); every later stats is skipped when there is no data row
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
nrow = ndata
array MN[nrow > 0 ? nrow : 1]            # integrator
array MA[nrow > 0 ? nrow : 1]            # accuracy
array MX[nrow > 0 ? nrow : 1]            # ns per revolution
array MY1[nrow > 0 ? nrow : 1]           # delta_error, clamped (NaN: not drawn)
array MY2[nrow > 0 ? nrow : 1]           # energy_drift, clamped (NaN: not drawn)
n = 0
# the columns by their headers ("name [unit]"), the CSV's first line; the header mode only while the CSV is read (the
# datablocks made below have no header line). The errors are read with column(): for an empty last field gnuplot
# 5.4's strcol returns a stale string, column() returns NaN
c_integrator = "integrator"; c_accuracy = "accuracy [-]"; c_ns = "ns_per_revolution [ns]"
c_delta = "delta_error [-]"; c_drift = "energy_drift [-]"
set datafile columnheaders
if (nrow > 0) {
    stats file using ((pos(column(c_accuracy)) && pos(column(c_ns))) ? \
        (n = n + 1, MN[n] = strcol(c_integrator), MA[n] = column(c_accuracy), MX[n] = column(c_ns), \
         MY1[n] = fin(column(c_delta)) ? clamp(column(c_delta)) : NaN, \
         MY2[n] = fin(column(c_drift)) ? clamp(column(c_drift)) : NaN) : 0, 0) nooutput
}
unset datafile columnheaders

# ---- the integrators present, in a fixed order: Simbody's integrators first (by the list KN below,
#      with or without the "Integrator" suffix), then any other name in order of first appearance.
#      Colours and markers: fixed for Simbody's integrators, then a list for any other name. Red is
#      kept for the Pareto front. ----------------------------------------------------------------------
array KN[9] = ["RungeKuttaMerson", "CPodes", "SemiExplicitEuler2", "RungeKuttaFeldberg", "RungeKutta3", \
               "RungeKutta2", "Verlet", "ExplicitEuler", "SemiExplicitEuler"]
array KC[9] = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"]
array KP[9] = [7, 5, 9, 13, 11, 7, 5, 9, 13]
array OC[5] = ["#000000", "#393b79", "#637939", "#843c39", "#7b4173"]
base(s) = (strlen(s) > 10 && s[strlen(s) - 9:strlen(s)] eq "Integrator") ? s[1:strlen(s) - 10] : s
names = "|"; NI = 0
do for [i = 1:n] { if (strstrt(names, "|" . MN[i] . "|") == 0) { names = names . MN[i] . "|"; NI = NI + 1 } }
array IN[NI > 0 ? NI : 1]
array IC[NI > 0 ? NI : 1]
array IP[NI > 0 ? NI : 1]
names = "|"; j = 0
do for [k = 1:9] {
    do for [i = 1:n] {
        if (base(MN[i]) eq KN[k] && strstrt(names, "|" . MN[i] . "|") == 0) {
            names = names . MN[i] . "|"; j = j + 1; IN[j] = MN[i]; IC[j] = KC[k]; IP[j] = KP[k]
        }
    }
}
nother = 0
do for [i = 1:n] {
    if (strstrt(names, "|" . MN[i] . "|") == 0) {
        names = names . MN[i] . "|"; j = j + 1; IN[j] = MN[i]
        IC[j] = OC[nother % 5 + 1]; IP[j] = 7 + 2 * (nother % 4); nother = nother + 1
    }
}

# ---- accuracy as a short label: "1e-6", "5e-7", "2.5e-6" (3 significant digits, no zero padding) ----
acc_e(a) = floor(log10(a) + 1e-9)
acc_m(a) = a / 10.0**acc_e(a)
acc_lbl(a) = (acc_m(a) >= 9.995) ? sprintf("1e%d", acc_e(a) + 1) : sprintf("%.3ge%d", acc_m(a), acc_e(a))

# ---- per panel: one datablock per integrator (its points in decreasing accuracy setting, i.e. the
#      loosest tolerance first), the Pareto front, and the y range ----------------------------------
array DONE[n > 0 ? n : 1]
array FR[n > 0 ? n : 1]
array CMD[2]
array NPT[2]
array YLO[2]
array YHI[2]
array CLAMPED[2]
xmin = 1e3; xmax = 1e6                   # the x axis of an empty figure
do for [i = 1:n] {
    if (i == 1 || MX[i] < xmin) { xmin = MX[i] }
    if (i == 1 || MX[i] > xmax) { xmax = MX[i] }
}
Y(p, i) = (p == 1) ? MY1[i] : MY2[i]
do for [p = 1:2] {
    CMD[p] = ""; PTS = ""; NPT[p] = 0; YLO[p] = 1; YHI[p] = 1; CLAMPED[p] = 0
    do for [i = 1:n] {
        if (fin(Y(p, i))) {
            NPT[p] = NPT[p] + 1
            if (NPT[p] == 1 || Y(p, i) < YLO[p]) { YLO[p] = Y(p, i) }
            if (NPT[p] == 1 || Y(p, i) > YHI[p]) { YHI[p] = Y(p, i) }
            if (Y(p, i) <= floor) { CLAMPED[p] = 1 }
        }
    }
    do for [g = 1:NI] {
        # this integrator's valid rows, largest accuracy setting first: cost, error, label
        do for [i = 1:n] { DONE[i] = !(MN[i] eq IN[g] && fin(Y(p, i))) }
        cnt = 0
        do for [i = 1:n] { cnt = cnt + !DONE[i] }
        if (cnt > 0) {
            eval sprintf("set print $P%d_%d", p, g)
            do for [s = 1:cnt] {
                best = 0
                do for [i = 1:n] {
                    if (!DONE[i] && (best == 0 || MA[i] > MA[best] || (MA[i] == MA[best] && MX[i] < MX[best]))) { best = i }
                }
                print sprintf("%.17g,%.17g,%s", MX[best], Y(p, best), acc_lbl(MA[best]))
                DONE[best] = 1
            }
            unset print
            CMD[p] = CMD[p] . sprintf("$P%d_%d using 1:2 with lines lw 1.5 lc rgb '%s' notitle, ", p, g, IC[g])
            PTS = PTS . sprintf("$P%d_%d using 1:2 with points pt %d ps 0.9 lc rgb '%s' notitle, ", p, g, IP[g], IC[g]) . \
                        sprintf("$P%d_%d using 1:2:3 with labels left offset 0.6, 0.45 font ',7' tc rgb '%s' notitle, ", p, g, IC[g])
        }
    }
    # Pareto front: not dominated (no other point at most as costly and at most as wrong, and strictly
    # better in one of the two), printed in increasing cost
    nfront = 0
    do for [i = 1:n] {
        FR[i] = 0
        if (fin(Y(p, i))) {
            dom = 0
            do for [j = 1:n] {
                if (j != i && fin(Y(p, j)) && MX[j] <= MX[i] && Y(p, j) <= Y(p, i) && (MX[j] < MX[i] || Y(p, j) < Y(p, i))) { dom = 1 }
            }
            FR[i] = dom ? 0 : 1
            nfront = nfront + FR[i]
        }
    }
    if (nfront > 0) {
        eval sprintf("set print $F%d", p)
        do for [s = 1:nfront] {
            best = 0
            do for [i = 1:n] {
                if (FR[i] == 1 && (best == 0 || MX[i] < MX[best] || (MX[i] == MX[best] && Y(p, i) > Y(p, best)))) { best = i }
            }
            print sprintf("%.17g,%.17g", MX[best], Y(p, best))
            FR[best] = 2
        }
        unset print
        # the front over the integrators' lines (it is dashed: a line under it still shows), under
        # the points and their labels
        CMD[p] = CMD[p] . sprintf("$F%d using 1:2 with lines lw 2 dt 2 lc rgb '#d62728' notitle, ", p)
    }
    CMD[p] = CMD[p] . PTS
    CMD[p] = (CMD[p] eq "") ? "NaN notitle" : CMD[p][1:strlen(CMD[p]) - 2]
}

# the legend (NaN plots, drawn in a panel of its own): the integrators, then the front
legend = ""
do for [g = 1:NI] {
    legend = legend . sprintf("NaN with linespoints lw 1.5 pt %d ps 0.9 lc rgb '%s' title '%s', ", IP[g], IC[g], IN[g])
}
legend = (n > 0) ? legend . "NaN with lines lw 2 dt 2 lc rgb '#d62728' title 'Pareto front'" : "NaN notitle"

# ---- axes (after every stats: stats obeys the ranges) --------------------------------------------
set logscale xy
# room on the right for the labels, which are written to the right of their points
set xrange [xmin / 2 : xmax * 4]
set format x "10^{%T}"
set format y "10^{%T}"
set mxtics default
set style textbox opaque noborder margins 2, 2
array TTL[2] = ["error of δ (relative to the analytic value)", "energy drift per revolution (relative)"]
array YL[2] = ["|δ_{Simbody} − δ_{analytic}| / δ_{analytic}", "relative energy drift per revolution"]
array COLN[2] = ["delta_error", "energy_drift"]

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
    set multiplot title "Simbody's integrators: cost per simulated revolution against error (Pareto front dashed)" font ",12"
    set border; set tics; set xtics; set mxtics default
    set grid xtics ytics mxtics lc rgb "#dddddd" lw 1
    set xlabel "cost per simulated revolution (ns, log scale)" font ",10"
    set tmargin at screen 0.86
    set bmargin at screen 0.25
    unset key

    do for [p = 1:2] {
        set title (TTL[p]) font ",11" offset 0, -0.3
        set ylabel (YL[p]) font ",10"
        if (p == 1) {
            set lmargin at screen 0.095
            set rmargin at screen 0.485
        } else {
            set lmargin at screen 0.585
            set rmargin at screen 0.975
        }
        # from the decade below the smallest value to a little above the decade of the largest (room
        # for the labels, written above and to the right of their points)
        if (NPT[p] == 0) { YLO[p] = 1e-10; YHI[p] = 1e-2 }
        lo = 10**floor(log10(YLO[p]) + 1e-9); hi = 10**(ceil(log10(YHI[p]) - 1e-9))
        if (lo <= floor) { lo = floor / 3 }
        hi = (hi < lo * 100) ? lo * 100 : hi * 3
        set yrange [lo : hi]
        if (hi / lo > 1e9) { set ytics 1e-16, 100 } else { set ytics 1e-17, 10 }
        unset label 5; unset arrow 1
        if (NPT[p] == 0) {
            set label 5 (n == 0 ? "no data rows in " . name . ".csv" : "no finite " . COLN[p] . " in the CSV") at graph 0.5, graph 0.5 center front boxed noenhanced
        }
        if (CLAMPED[p]) {
            set arrow 1 from graph 0, first floor to graph 1, first floor nohead dt 3 lc rgb "#999999" back
        }
        eval "plot " . CMD[p]
    }

    # the legend and the note: an empty panel as wide as the figure (a key is laid out within the
    # width of its own panel, too narrow in either data panel for a horizontal legend)
    unset label 5; unset arrow 1
    unset title; unset xlabel; unset ylabel; unset border; unset tics; unset grid
    set lmargin at screen 0.02
    set rmargin at screen 0.98
    set tmargin at screen 0.15
    set bmargin at screen 0.02
    set key at screen 0.5, screen 0.11 center center horizontal maxrows 2 reverse Left samplen 3 font ",9" width 1 box lc rgb "#bbbbbb" noenhanced
    if (n == 0) { unset key }
    set label 8 "small numbers next to the points: the accuracy setting (loosest first along each line)" . \
        (CLAMPED[1] || CLAMPED[2] ? ";  0 shown at 10^{-17} (dotted line; below double precision)" : "") \
        at screen 0.5, screen 0.045 center font ",9" tc rgb "#555555"
    eval "plot " . legend
    unset label 8
    unset key
    unset multiplot
    unset output
}
