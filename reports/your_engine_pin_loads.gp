# your_engine_pin_loads.gp -- the scene sections' pin-load polar diagrams (topic "Loads over a working cycle"): the
# closed forms' crank-pin and main-bearing forces over one working cycle, one panel per scene.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/your_engine_pin_loads.gp
#
# Reads  in_dir/your_engine_pin_loads.csv (columns by their header names, validation/src/your_engine/loads.cc)
# Writes out_dir/your_engine_pin_loads.svg and out_dir/your_engine_pin_loads.png
#
# Panel i (scene_index i, from 0: the scene's place among the sections) draws the tip of the force vector over the
# cycle at the scene's own speed with its gas and gravity: the crank-pin force of cylinder 0 in the crank's own frame
# (x: radial, outward along the throw; y: tangential, the direction of rotation) in blue, the main-bearing force in
# the frame's X, Y in red. Equal axes, in N (SI prefixes: k, M). The scene's name (last column, so that a name with a
# comma cannot shift the numbers) is the panel's title. At most 8 panels (2 rows). The rows of each scene come
# together, in order of phi_deg (crankcheck writes its tables sorted: scene_index, phi_deg).

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "your_engine_pin_loads"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
nlines = 0
stats file using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . file . " is missing or empty (not even a header line)"; exit status 1 }
set datafile columnheaders
SCENE = "scene_index [-]"
nscenes = 0
if (nlines > 1) { stats file using (nscenes = (column(SCENE) + 1 > nscenes ? column(SCENE) + 1 : nscenes), 0) nooutput }
nscenes = int(nscenes)
npanels = nscenes > 8 ? 8 : nscenes
array TITLE[8]
do for [i = 1:8] { TITLE[i] = sprintf("scene %d", i) }
if (nscenes > 0) { stats file using (column(SCENE) < 8 ? TITLE[int(column(SCENE)) + 1] = strcol("scene") : 0, 0) nooutput }
# The rows of each scene run together in the sorted CSV: their first and last data row found in one pass, so that
# each curve reads only its own rows (every ::first::last), not the whole file through a filter.
array FIRST[8]
array LAST[8]
do for [i = 1:8] { FIRST[i] = -1; LAST[i] = -2 }
mark(i, row) = (i < 8 ? (FIRST[i + 1] < 0 ? FIRST[i + 1] = row : 0, LAST[i + 1] = row) : 0)
if (nscenes > 0) { stats file using (mark(int(column(SCENE)), int($0)), 0) nooutput }

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
cols = npanels > 4 ? int((npanels + 1) / 2) : (npanels > 0 ? npanels : 1)
rows = npanels > 4 ? 2 : 1
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
    set multiplot layout rows, cols title "Your engines' pin loads over a working cycle [N] (closed forms): crank pin in the crank's frame (blue), main bearing (red)" font ",11" margins 0.05, 0.98, 0.12, 0.9 spacing 0.06, 0.1
    set size ratio -1
    set grid lc rgb "#e0e0e0"
    set xtics font ",7" rotate by 45 right
    set ytics font ",7"
    set format x "%.1s%c"
    set format y "%.1s%c"
    set xzeroaxis lc rgb "#999999"
    set yzeroaxis lc rgb "#999999"
    if (npanels == 0) {
        set label 5 "no rows in the CSV" at graph 0.5, graph 0.5 center front
        plot [0:1] [0:1] NaN notitle
    }
    do for [p = 1:npanels] {
        set title TITLE[p] noenhanced font ",9"
        if (p == 1) { set key at screen 0.5, screen 0.03 center center horizontal font ",9" samplen 2 } else { unset key }
        # A scene index without rows: one row read, its values NaN.
        ok = FIRST[p] >= 0; r0 = ok ? FIRST[p] : 0; r1 = ok ? LAST[p] : 0
        plot file every ::r0::r1 using (ok ? column("crank_pin_radial [N]") : NaN):"crank_pin_tangential [N]" with lines lw 1.5 lc rgb "#1f77b4" title "crank pin", \
             file every ::r0::r1 using (ok ? column("bearing_x [N]") : NaN):"bearing_y [N]" with lines lw 1.5 lc rgb "#d62728" title "main bearing"
    }
    unset multiplot
    unset output
}
