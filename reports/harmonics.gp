# harmonics.gp -- which harmonics of the gravity torque Q survive, per cylinder count k and cycle.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/harmonics.gp
#
# Reads  in_dir/harmonics.csv (validation/src/parts/harmonics.cc declares its columns: one ENGINE_amplitude per reference
#        engine), each column by its header ("analytic_amplitude [N m]")
# Writes out_dir/harmonics.svg and out_dir/harmonics.png
#
# Two stacked panels (two-stroke above, four-stroke below). Each cell (n, k) is coloured by
# log10 of Simbody's amplitude (simbody_amplitude), clamped to [-17, 0] (0 or below 1e-17 is drawn as -17). An open circle
# marks analytic_amplitude > 1e-12 (the prediction); a small cross marks paper_nonzero == 1 (the
# paper's table 1; 0 or empty draws nothing). A cell with no row in the CSV stays light grey.
# Rows may come in any order; a missing cycle leaves its panel empty with a note.

# The reference engine drawn beside the closed forms: crankcheck passes the first one in play (an engine that sat out
# is not drawn); alone, Simbody.
if (!exists("reference")) reference = "simbody"
if (!exists("reference_title")) reference_title = "Simbody"

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "harmonics"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
lz(a) = (a == a) ? ((a > 1e-17) ? ((a < 1) ? log10(a) : 0) : -17) : NaN
amp_threshold = 1e-12

# ---- which cycles have rows ---------------------------------------------------------------------
present = "|"
# ---- number of data rows: a constant-only "using" counts the header line too (no warning even for a
#      header-only CSV); every later stats is skipped when there is no data row ----------------------
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
# The count above includes the header line; from here on it names the columns.
set datafile columnheaders

if (ndata > 0) {
    stats file using (key = strcol("cycle") . "|", (strstrt(present, "|" . key) == 0 ? present = present . key : 0), 0) nooutput
}

has(c) = strstrt(present, "|" . c . "|") > 0

# ---- style --------------------------------------------------------------------------------------
set palette defined (0 "#30123b", 1 "#3b528b", 2 "#21918c", 3 "#5ec962", 4 "#fde725")
set cbrange [-17:0]
set cbtics -16, 2, 0 font ",9"
set cblabel "log_{10}(" . reference_title . " amplitude / energy scale)" font ",9" offset -0.5, 0
set colorbox user origin screen 0.885, screen 0.145 size screen 0.018, screen 0.715
set xtics 1, 1, 24 scale 0 font ",9"
set ytics 1, 1, 12 scale 0 font ",9"
set ylabel "cylinders k" font ",10"
set lmargin at screen 0.07
set rmargin at screen 0.865
set object 1 rectangle from graph 0, 0 to graph 1, 1 fillcolor rgb "#e6e6e6" fillstyle solid 1.0 noborder behind

# paper_nonzero is tested with column("paper_nonzero") == 1: for an empty field gnuplot 5.4's strcol returns a stale
# string (seen: "1"), so a string comparison would draw crosses the CSV does not ask for; column() of an empty field is
# missing (the row is skipped).
# cells, then each marker twice (a wide white stroke under a thin black one: visible on any colour)
cells(c)   = sprintf("file using 'n [-]':(strcol('cycle') eq '%s' ? column('k [-]') : NaN):(0.5):(0.5):(lz(column('%s_amplitude [N m]'))) with boxxyerror fillstyle solid 1.0 noborder lc palette notitle", c, reference)
circles(c) = sprintf("file using 'n [-]':(strcol('cycle') eq '%s' && column('analytic_amplitude [N m]') > amp_threshold ? column('k [-]') : NaN) with points pt 6 ps 1.25 lw 3.5 lc rgb 'white' notitle, ", c) . \
             sprintf("file using 'n [-]':(strcol('cycle') eq '%s' && column('analytic_amplitude [N m]') > amp_threshold ? column('k [-]') : NaN) with points pt 6 ps 1.25 lw 1.3 lc rgb 'black' notitle", c)
crosses(c) = sprintf("file using 'n [-]':(strcol('cycle') eq '%s' && column('paper_nonzero') == 1 ? column('k [-]') : NaN) with points pt 2 ps 0.7 lw 3.5 lc rgb 'white' notitle, ", c) . \
             sprintf("file using 'n [-]':(strcol('cycle') eq '%s' && column('paper_nonzero') == 1 ? column('k [-]') : NaN) with points pt 2 ps 0.7 lw 1.3 lc rgb 'black' notitle", c)
# the three markers only appear in the legend (NaN plots), drawn in the lower panel's key
legend = "NaN with points pt 6 ps 1.25 lw 1.3 lc rgb 'black' title 'analytic amplitude > 10^{-12} (prediction)', " . \
         "NaN with points pt 2 ps 0.7 lw 1.3 lc rgb 'black' title 'nonzero in the paper''s table 1', " . \
         "NaN with boxes fillstyle solid 1.0 lc rgb '#e6e6e6' title 'no row in the CSV'"

# ---- a plot command per panel (stats run before any range is set: stats obeys ranges); the marker plots are included only if they have points, so a CSV
# without predictions or without paper flags draws no warning
nc = 0; np = 0
array CYC[2] = ["two-stroke", "four-stroke"]
array CMD[2]
do for [p = 1:2] {
    c = CYC[p]
    if (has(c)) {
        nc = 0; np = 0
        # apart: a row whose paper_nonzero is empty is skipped by the stats that reads it
        stats file using ((strcol("cycle") eq c && column("analytic_amplitude [N m]") > amp_threshold) ? nc = nc + 1 : 0, 0) nooutput
        stats file using ((strcol("cycle") eq c && column("paper_nonzero") == 1) ? np = np + 1 : 0, 0) nooutput
        CMD[p] = cells(c) . (nc > 0 ? ", " . circles(c) : "") . (np > 0 ? ", " . crosses(c) : "")
    } else {
        CMD[p] = "NaN notitle"
    }
}

set xrange [0.5:24.5]
set yrange [0.5:12.5]

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
    set multiplot title "Harmonics of Q from a DFT of " . reference_title . "'s Q(φ): colour; analytic prediction: circles; paper's table 1: crosses" font ",12"

    do for [p = 1:2] {
        c = CYC[p]
        set title (CYC[p]) font ",11" offset 0, -0.3
        if (p == 1) {
            set tmargin at screen 0.86
            set bmargin at screen 0.575
            set xlabel ""
            unset label 6
            set colorbox
            unset key
        } else {
            set tmargin at screen 0.455
            set bmargin at screen 0.145
            set xlabel "harmonic order n (multiples of the crank frequency)" font ",10" offset 0, 0.3
            unset colorbox
            set label 6 "0 and amplitudes below 10^{-17} are drawn as -17" at screen 0.985, screen 0.035 right font ",9" tc rgb "#444444"
            set key at screen 0.40, screen 0.035 center center horizontal reverse Left samplen 1.5 font ",9" box lc rgb "#bbbbbb"
        }
        unset label 5
        if (!has(c)) { set label 5 "no " . c . " rows in the CSV" at graph 0.5, graph 0.5 center front }
        eval "plot " . CMD[p] . (p == 2 ? ", " . legend : "")
    }
    unset multiplot
    unset output
}
