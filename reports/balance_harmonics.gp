# balance_harmonics.gp -- which harmonics of the shaking force and couple remain, per engine layout.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/balance_harmonics.gp
#
# Reads  in_dir/balance_harmonics.csv (columns by their header names, validation/src/parts/balance.cc)
# Writes out_dir/balance_harmonics.svg and out_dir/balance_harmonics.png
#
# Two panels side by side: the shaking force (left) and the couple about X and Y (right). Each cell (n, layout) is
# coloured by log10 of the amplitude relative to the force (moment) scale, clamped to [-17, 0]; a harmonic that
# vanishes exactly by the layout's symmetry (force_vanishes / couple_vanishes = 1) is drawn white with a small dot.
# Layouts are labelled on the y axis from the layout column. Rows may come in any order.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "balance_harmonics"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
lz(a) = (a == a) ? ((a > 1e-17) ? ((a < 1) ? log10(a) : 0) : -17) : NaN

nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
ndata = nlines - 1
set datafile columnheaders
nlayouts = 1
if (ndata > 0) {
    stats file using "layout_index [-]" nooutput
    nlayouts = STATS_max + 1
}

set palette defined (0 "#30123b", 1 "#3b528b", 2 "#21918c", 3 "#5ec962", 4 "#fde725")
set cbrange [-17:0]
set cbtics -16, 2, 0 font ",9"
set cblabel "log_{10}(amplitude / scale)" font ",9" offset -0.5, 0
set colorbox user origin screen 0.915, screen 0.12 size screen 0.018, screen 0.74
set xtics 1, 1, 8 scale 0 font ",9"
set ytics scale 0 font ",8" noenhanced
set xrange [0.5:8.5]
set yrange [-0.5:nlayouts - 0.5]
set object 1 rectangle from graph 0, 0 to graph 1, 1 fillcolor rgb "#e6e6e6" fillstyle solid 1.0 noborder behind

# column c: "force_relative [-]" or "couple_relative [-]"; the vanishing flag in column f: "force_vanishes" or
# "couple_vanishes"; the layouts labelled on the force's panel
cells(c, f) = sprintf("file using 'n [-]':'layout_index [-]':(0.5):(0.5):(column('%s') == 1 ? NaN : lz(column('%s')))%s with boxxyerror fillstyle solid 1.0 noborder lc palette notitle, ", f, c, c eq "force_relative [-]" ? ":ytic(strcol('layout'))" : "") . \
              sprintf("file using 'n [-]':(column('%s') == 1 ? column('layout_index [-]') : NaN):(0.5):(0.5) with boxxyerror fillstyle solid 1.0 noborder lc rgb 'white' notitle, ", f) . \
              sprintf("file using 'n [-]':(column('%s') == 1 ? column('layout_index [-]') : NaN) with points pt 7 ps 0.35 lc rgb '#555555' notitle", f)

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
    set multiplot title "Shaking force and couple per harmonic (closed form; Simbody's DFT agrees)" font ",12"
    set label 6 "white with a dot: vanishes exactly by symmetry; 0 and amplitudes below 10^{-17} are drawn as -17" at screen 0.5, screen 0.03 center font ",9" tc rgb "#444444"
    set tmargin at screen 0.88
    set bmargin at screen 0.15
    set xlabel "harmonic n" font ",10" offset 0, 0.5

    set title "shaking force F_s" font ",11"
    set lmargin at screen 0.19
    set rmargin at screen 0.53
    unset colorbox
    if (ndata > 0) { eval "plot " . cells("force_relative [-]", "force_vanishes") } else { set label 5 "no rows in the CSV" at graph 0.5, graph 0.5 center front; plot NaN notitle }

    set title "couple about X and Y (about the engine's middle)" font ",11"
    set lmargin at screen 0.555
    set rmargin at screen 0.895
    unset ytics
    set colorbox
    if (ndata > 0) { eval "plot " . cells("couple_relative [-]", "couple_vanishes") } else { plot NaN notitle }
    set ytics scale 0 font ",8" noenhanced
    unset label 6
    unset multiplot
    unset output
}
