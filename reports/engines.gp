# engines.gp -- the engines' league table: cost per evaluation against the worst error, one point per engine and k.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/engines.gp
#
# Reads  in_dir/engines_league.csv (validation/src/parts/engines.cc declares its columns), each column by its header
#        ("ns_per_eval [ns]")
# Writes out_dir/engines.svg and out_dir/engines.png
#
# x = ns per evaluation (every quantity at one crank angle; log), y = the engine's worst error over every quantity
# and every cross-checked case, relative to the quantity's scale (log; anything below 1e-17 drawn at 1e-17). k = 1:
# filled circle with the engine's name; k = 12: open circle at the same height. Down and left is better.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "engines"
file = in_dir . "/engines_league.csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v

nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
# The count above includes the header line; from here on it names the columns.
set datafile columnheaders
# The cost of the rows of k = `k`, NaN for the others.
cost(k) = column("k [-]") == k ? column("ns_per_eval [ns]") : NaN

set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set grid xtics ytics lc rgb "#dddddd" lw 1
set xlabel "cost per evaluation (ns, log scale): filled k = 1, open k = 12"
set ylabel "worst error / scale over the campaign (dimensionless)"
set key off
set offsets graph 0.05, graph 0.35, graph 0.1, graph 0.1
set label 9 "0 shown at 10^{-17} (below double precision)" at graph 0.99, graph 0.03 right font ",9" tc rgb "#444444"
set style textbox opaque noborder margins 1, 1

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
    set title "Engines: cost per evaluation against worst error" font ",13"
    plot file using (cost(1)):(clamp(column("worst_rel_error [-]"))):"engine" with labels left offset 1, 0.6 boxed font ",10" noenhanced notitle, \
         file using (cost(1)):(clamp(column("worst_rel_error [-]"))) with points pt 7 ps 1.5 lc rgb "#1f77b4" notitle, \
         file using (cost(12)):(clamp(column("worst_rel_error [-]"))) with points pt 6 ps 1.5 lc rgb "#d62728" notitle
    unset output
}
