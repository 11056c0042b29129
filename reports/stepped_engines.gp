# stepped_engines.gp -- the physics engines people ship: each engine's error against its time step.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/stepped_engines.gp
#
# Reads  in_dir/stepped_engines.csv (validation/src/parts/stepped_engines.cc declares its columns), each column by its
#        header ("dt [s]", "positions [-]", "loads [-]", "series [-]", "label")
# Writes out_dir/stepped_engines.svg and out_dir/stepped_engines.png
#
# Two log-log panels, x = the time step dt [s]: left the worst error of the positions (x_p, the loops' separation),
# right of the loads (joint forces, drive torque), each relative to its scale over one turn. One line per series (an
# engine at one of its settings), labelled by the label column. Anything below 1e-17 (or NaN: not reported) is left
# out of its panel. The slope is the observed order; a flat line does not converge.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "stepped_engines"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
keep(v) = (v == v && v >= floor && v < 1e300) ? v : NaN
# One colour per series, set here: no linetype another script may have changed in the same gnuplot.
colours = "#1b9e77 #d95f02 #7570b3 #e7298a #66a61e #e6ab02 #a6761d #666666 #1f78b4 #e31a1c #33a02c #6a3d9a #b15928 #000000"
colour(i) = word(colours, (i - 1) % words(colours) + 1)

nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
if (nlines < 2) { print "error: " . file . " has no data row"; exit status 1 }
set datafile columnheaders
N = 0
stats file using (N = (column("series [-]") > N ? column("series [-]") : N), 1) nooutput
array L[N]
do for [i = 1:N] {
    label = ""
    stats file using (column("series [-]") == i ? (label = strcol("label"), 1) : 1) nooutput
    L[i] = label
}

set logscale xy
set format y "10^{%L}"
set format x "10^{%L}"
set xlabel "time step dt [s]"
set grid
set key outside right top noenhanced

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1200,520 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 1200,520 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 1200,520 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    set multiplot layout 1,2
    set ylabel "positions: worst error / scale [-]"
    unset key
    plot for [i = 1:N] file using (column("series [-]") == i ? column("dt [s]") : NaN):(keep(column("positions [-]"))) \
        with linespoints lw 2 pt 7 lc rgb colour(i) title L[i]
    set key outside right top noenhanced
    set ylabel "loads: worst error / scale [-]"
    plot for [i = 1:N] file using (column("series [-]") == i ? column("dt [s]") : NaN):(keep(column("loads [-]"))) \
        with linespoints lw 2 pt 7 lc rgb colour(i) title L[i]
    unset multiplot
    unset output
}
