# error_vs_lambda.gp -- relative error of each closed form against lambda = r / l.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/error_vs_lambda.gp
#
# Reads  in_dir/error_vs_lambda.csv   its columns by their headers (below: quantity, method, lambda, max_rel_error)
# Writes out_dir/error_vs_lambda.svg and out_dir/error_vs_lambda.png
#
# Left panel: piston kinematics (x_p, v_p, a_p; Norton's two-term form and, if present, the
# analytic library against Simbody). Right panel: gravity torque Q (exact Fourier series of
# order 2..12, the paper's eq (15) and eq (5) as printed, analytic against Simbody) plus U.
# Reads also in_dir/your_engine.csv (the scene sections' facts, columns scene, given and lambda [-]) when it is there:
# each scene the user gave (given = "user") is marked by a dash-dotted vertical line at its lambda.
# Any (quantity, method) pair absent from the CSV is left out of the plot and the legend.
# Rows may come in any order. Errors of 0 (or below 1e-17) are drawn at 1e-17.

# The reference engine drawn beside the closed forms: crankcheck passes the first one in play (an engine that sat out
# is not drawn); alone, Simbody.
if (!exists("reference")) reference = "simbody"
if (!exists("reference_title")) reference_title = "Simbody"

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "error_vs_lambda"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
fin(v) = (v == v && abs(v) < 1e300)      # false for nan and inf: such values are not drawn
eps = 2.220446049250313e-16

# ---- number of data rows: a constant-only "using" counts the header line too (no warning even for a
#      header-only CSV); every later stats is skipped when there is no data row ----------------------
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1

# ---- the columns, by their headers ("name [unit]"): the CSV's first line names them; the datablocks made below have
#      no header line, so the header mode is on only while the CSV is read -------------------------------------------
c_quantity = "quantity"; c_method = "method"; c_lambda = "lambda [-]"; c_rel = "max_rel_error [-]"
set datafile columnheaders

# ---- which (quantity, method) pairs have at least one valid number --------------------------
# (also the smallest and largest lambda, so the x range can widen past 0.01 .. 0.95 if needed)
present = "|"; lmin = 0.01; lmax = 0.95
if (ndata > 0) {
    stats file using (key = strcol(c_quantity) . ":" . strcol(c_method) . "|", \
        (fin(column(c_rel)) && column(c_lambda) > 0 && strstrt(present, "|" . key) == 0 ? present = present . key : 0), \
        (column(c_lambda) > 0 && column(c_lambda) < lmin ? lmin = column(c_lambda) : 0), \
        (column(c_lambda) > lmax ? lmax = column(c_lambda) : 0), 0) nooutput
}

has(q, m) = strstrt(present, "|" . q . ":" . m . "|") > 0

# ---- your engines: each scene the user gave (in_dir/your_engine.csv, given = "user", by the columns scene and
#      lambda [-]) is marked by a dash-dotted vertical line at its lambda, labelled with its name; none in the default
#      campaign (its scenes are "example") or when the file is missing --------------------------------------------
yours_lambda = ""; yours_name = ""
yfile = in_dir . "/your_engine.csv"
ylines = 0
stats yfile using (ylines = ylines + 1, 1) nooutput
if (ylines > 0) {
    stats yfile using (u = (strcol("given") eq "user" && fin(column("lambda [-]")) && column("lambda [-]") > 0), \
        yours_lambda = u ? yours_lambda . sprintf("%.17g ", column("lambda [-]")) : yours_lambda, \
        yours_name = u ? yours_name . strcol("scene") . "|" : yours_name, 0) nooutput
}
nyours = words(yours_lambda)

# ---- the candidate series: quantity, method, legend title, line style -------------------------
N = 17
array SQ[N]; array SM[N]; array ST[N]; array SP[N]
# left panel (SP = 1)
i = 0
do for [q in "x_p v_p a_p"] {
    i = i + 1
    SQ[i] = q; SM[i] = "norton_two_term"; SP[i] = 1
    ST[i] = q . " Norton two-term"
    SQ[i+3] = q; SM[i+3] = "analytic_vs_" . reference; SP[i+3] = 1
    ST[i+3] = q . " analytic vs " . reference_title
}
# right panel (SP = 2)
i = 6
do for [n = 2:12:2] {
    i = i + 1
    SQ[i] = "Q"; SM[i] = sprintf("fourier_order_%d", n); SP[i] = 2
    ST[i] = sprintf("Q Fourier order %d", n)
}
SQ[13] = "Q"; SM[13] = "paper_eq15_printed";  ST[13] = "Q eq (15) as printed";  SP[13] = 2
SQ[14] = "Q"; SM[14] = "paper_eq5_printed";   ST[14] = "Q eq (5) as printed";   SP[14] = 2
SQ[15] = "Q"; SM[15] = "analytic_vs_" . reference; ST[15] = "Q analytic vs " . reference_title; SP[15] = 2
SQ[16] = "U"; SM[16] = "analytic_vs_" . reference; ST[16] = "U analytic vs " . reference_title; SP[16] = 2
SQ[17] = "U"; SM[17] = "paper_eq5_printed";   ST[17] = "U eq (5) as printed";   SP[17] = 2

# styles: kinematics x_p blue, v_p orange, a_p red; Norton solid + filled, Simbody dashed + open
set style line 1 lc rgb "#1f77b4" lw 2 pt 7 ps 0.8
set style line 2 lc rgb "#ff7f0e" lw 2 pt 5 ps 0.8
set style line 3 lc rgb "#d62728" lw 2 pt 9 ps 0.9
set style line 4 lc rgb "#1f77b4" lw 1.5 dt 2 pt 6 ps 0.8
set style line 5 lc rgb "#ff7f0e" lw 1.5 dt 2 pt 4 ps 0.8
set style line 6 lc rgb "#d62728" lw 1.5 dt 2 pt 8 ps 0.9
# Fourier orders 2..12: a colour ramp from dark violet (order 2) to orange (order 12)
set style line 7  lc rgb "#0d0887" lw 1.5 pt 7 ps 0.6
set style line 8  lc rgb "#5302a3" lw 1.5 pt 7 ps 0.6
set style line 9  lc rgb "#8b0aa5" lw 1.5 pt 7 ps 0.6
set style line 10 lc rgb "#b83289" lw 1.5 pt 7 ps 0.6
set style line 11 lc rgb "#db5c68" lw 1.5 pt 7 ps 0.6
set style line 12 lc rgb "#f48849" lw 1.5 pt 7 ps 0.6
set style line 13 lc rgb "#000000" lw 2   pt 9 ps 0.9
set style line 14 lc rgb "#8c564b" lw 2   dt 2 pt 5 ps 0.8
set style line 15 lc rgb "#2ca02c" lw 1.5 pt 7 ps 0.8
set style line 16 lc rgb "#17becf" lw 1.5 dt 2 pt 6 ps 0.9
set style line 17 lc rgb "#7f7f7f" lw 2   dt 4 pt 4 ps 0.8

# ---- one comma-separated datablock per present series (robust to any row order) ---------------
cmd1 = ""; cmd2 = ""
do for [i = 1:N] {
    if (has(SQ[i], SM[i])) {
        eval sprintf("set table $S%d separator comma", i)
        plot file using (column(c_lambda)):(clamp(column(c_rel))) with table \
            if (strcol(c_quantity) eq SQ[i] && strcol(c_method) eq SM[i] && fin(column(c_rel)) && column(c_lambda) > 0)
        unset table
        c = sprintf("$S%d using 1:2 smooth unique with linespoints ls %d title \"%s\", ", i, i, ST[i])
        if (SP[i] == 1) { cmd1 = cmd1 . c } else { cmd2 = cmd2 . c }
    }
}
unset datafile columnheaders
cmd1 = (cmd1 eq "") ? "NaN notitle" : cmd1[1:strlen(cmd1) - 2]
cmd2 = (cmd2 eq "") ? "NaN notitle" : cmd2[1:strlen(cmd2) - 2]

# ---- common axes ------------------------------------------------------------------------------
set logscale xy
set xrange [lmin / 1.12 : lmax * 1.06]
set yrange [floor : 1<*]
set format y "10^{%T}"
set xtics ("0.01" 0.01, "0.02" 0.02, "0.05" 0.05, "0.1" 0.1, "0.2" 0.2, "0.4" 0.4, "0.95" 0.95)
set mxtics default
set ytics 1e-16, 100
set grid xtics ytics lc rgb "#dddddd" lw 1
set xlabel "crank ratio λ = r / l  (dimensionless, log scale)"
set tmargin at screen 0.84
set bmargin at screen 0.36

# machine epsilon: a dashed horizontal line with its own legend entry (a label would sit on data)
set style line 20 lc rgb "#444444" lw 1.5 dt 2
epsline = "eps with lines ls 20 title \"machine epsilon 2.2e-16\""
cmd1 = (cmd1 eq "NaN notitle") ? epsline : cmd1 . ", " . epsline
cmd2 = (cmd2 eq "NaN notitle") ? epsline : cmd2 . ", " . epsline
# largest engine lambda: a dotted vertical line, labelled just above the frame
set arrow 2 from first 0.4, graph 0 to first 0.4, graph 1 nohead dt 3 lw 2 lc rgb "#444444" back
set label 2 "largest engine λ = 0.4" at first 0.4, graph 1 center offset 0, 0.55 font ",9" tc rgb "#444444"
# your engines' lambdas: dash-dotted green lines, each labelled with its scene's name inside the frame, read upward
rest = yours_name
do for [i = 1:nyours] {
    L = real(word(yours_lambda, i))
    p = strstrt(rest, "|")
    yname = rest[1:p - 1]
    rest = rest[p + 1:]
    if (L < lmin) { lmin = L }
    if (L > lmax) { lmax = L }
    set arrow (10 + i) from first L, graph 0 to first L, graph 1 nohead dt 4 lw 2 lc rgb "#2ca02c" back
    set label (10 + i) "your engine: " . yname at first L, graph 0.97 right rotate by 90 offset -0.7, 0 font ",8" tc rgb "#2ca02c" noenhanced
}
set xrange [lmin / 1.12 : lmax * 1.06]

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
    set multiplot title "Largest relative error over a crank revolution against the crank ratio λ" font ",13"
    set label 9 "0 and values below 10^{-17} drawn at 10^{-17} (below double precision)" at screen 0.5, screen 0.03 center font ",9" tc rgb "#444444"

    set title "piston kinematics" font ",11" offset 0, 0.6
    set ylabel "max relative error (dimensionless)"
    set lmargin at screen 0.085
    set rmargin at screen 0.475
    set key at screen 0.28, screen 0.255 center top vertical maxrows 4 Left reverse width -4 samplen 2.5 font ",9" spacing 1.0 box lc rgb "#bbbbbb"
    eval "plot " . cmd1
    unset label 9

    set title "gravity torque Q (and potential energy U)" font ",11" offset 0, 0.6
    set ylabel ""
    set lmargin at screen 0.58
    set rmargin at screen 0.97
    set key at screen 0.775, screen 0.255 center top vertical maxrows 6 Left reverse width -4 samplen 2.5 font ",9" spacing 1.0 box lc rgb "#bbbbbb"
    eval "plot " . cmd2
    unset multiplot
    unset output
}
