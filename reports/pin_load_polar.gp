# pin_load_polar.gp -- the crank-pin and main-bearing forces over a working cycle as polar diagrams (after Norton's
# Program ENGINE), one panel per scene, every exact engine.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/pin_load_polar.gp
#
# Reads  in_dir/pin_load_polar.csv (columns by their header names, validation/src/parts/pin_load_polar.cc)
# Writes out_dir/pin_load_polar.svg and out_dir/pin_load_polar.png
#
# Panel i (scene_index i, from 0) draws the tip of the force vector over the cycle: the crank-pin force of cylinder 0
# in the crank's own frame (x: radial, outward along the throw; y: tangential, the direction of rotation) in blue,
# the main-bearing force in the frame's X, Y in red; analytic as lines, Simbody (engine "simbody") as dots. Equal
# axes, in N (SI prefixes: k, M). The scene's name (last column, so that a name with a comma cannot shift the numbers) is the panel's
# title. At most 8 panels (2 rows). The rows of each (scene, engine) come together, in order of phi_deg (crankcheck
# writes its tables sorted: scene_index, engine, phi_deg).

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "pin_load_polar"
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
# The rows of each (scene, engine) run together in the sorted CSV: their first and last data row found
# in one pass, so that each curve reads only its own rows (every ::first::last), not the whole file through a filter.
array FIRST_A[8]
array LAST_A[8]
array FIRST_S[8]
array LAST_S[8]
do for [i = 1:8] { FIRST_A[i] = -1; LAST_A[i] = -2; FIRST_S[i] = -1; LAST_S[i] = -2 }
mark(i, eng, row) = (i < 8 ? (eng eq "analytic" ? (FIRST_A[i + 1] < 0 ? FIRST_A[i + 1] = row : 0, LAST_A[i + 1] = row) \
                                                : eng eq "simbody" ? (FIRST_S[i + 1] < 0 ? FIRST_S[i + 1] = row : 0, LAST_S[i + 1] = row) : 0) : 0)
if (nscenes > 0) { stats file using (mark(int(column(SCENE)), strcol("engine"), int($0)), 0) nooutput }

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
    set multiplot layout rows, cols title "Pin loads over a working cycle [N]: crank pin in the crank's frame (blue), main bearing (red); Simbody as dots" font ",11" margins 0.05, 0.98, 0.12, 0.9 spacing 0.06, 0.1
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
        i = p - 1
        set title TITLE[p] noenhanced font ",9"
        # The key goes beside the last panel (in the empty slot of an odd count), or below the panels.
        if (p == 1) {
            if (npanels % 2 == 1 && npanels > 4) { set key at screen 0.985, screen 0.3 right center vertical font ",9" samplen 2 } else { set key at screen 0.5, screen 0.03 center center horizontal font ",9" samplen 2 }
        } else { unset key }
        # An engine without rows in this scene: one row read, its values NaN (every with a negative bound reads all).
        ok_a = FIRST_A[p] >= 0; a0 = ok_a ? FIRST_A[p] : 0; a1 = ok_a ? LAST_A[p] : 0
        ok_s = FIRST_S[p] >= 0; s0 = ok_s ? FIRST_S[p] : 0; s1 = ok_s ? LAST_S[p] : 0
        plot file every ::a0::a1 using (ok_a ? column("crank_pin_radial [N]") : NaN):"crank_pin_tangential [N]" with lines lw 1.5 lc rgb "#1f77b4" title "crank pin (analytic)", \
             file every 3::s0::s1 using (ok_s ? column("crank_pin_radial [N]") : NaN):"crank_pin_tangential [N]" with points pt 7 ps 0.3 lc rgb "#0b3d91" title "crank pin (Simbody)", \
             file every ::a0::a1 using (ok_a ? column("bearing_x [N]") : NaN):"bearing_y [N]" with lines lw 1.5 lc rgb "#d62728" title "main bearing (analytic)", \
             file every 3::s0::s1 using (ok_s ? column("bearing_x [N]") : NaN):"bearing_y [N]" with points pt 7 ps 0.3 lc rgb "#7f0000" title "main bearing (Simbody)"
    }
    unset multiplot
    unset output
}
