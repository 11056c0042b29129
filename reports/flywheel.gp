# flywheel.gp -- report part `flywheel`: flywheel sizing, the exact inertia against Norton's method and Simbody's run.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/flywheel.gp
#
# Reads  in_dir/flywheel.csv          its columns by their headers (below: scene, flywheel_inertia, exact_delta,
#                                     simbody_delta: Simbody's run)
#        in_dir/flywheel_norton.csv   its columns by their headers (below: speed_rpm, k, norton_error)
# Writes out_dir/flywheel.svg and out_dir/flywheel.png
#
# Left: delta against the flywheel inertia (log-log), one line per scene (the exact energy integral), Simbody's run as
# dots (empty cells: not run there), the sizing target delta = 0.01 dashed. Right: Norton's error in the inertia
# (norton / exact - 1, in %) against k, one line per speed. Each series' rows come together, in order (crankcheck sorts
# the tables by their first columns).

# The engine whose free run is drawn: crankcheck passes the first in play whose run takes the loads ("" when none is,
# then no run is drawn); alone, Simbody.
if (!exists("loaded_run")) loaded_run = "simbody"

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "flywheel"
curve = in_dir . "/flywheel.csv"
sweep = in_dir . "/flywheel_norton.csv"

reset
set encoding utf8
set datafile separator ","
nlines = 0
stats curve using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . curve . " is missing or empty (not even a header line)"; exit status 1 }
nsweep = 0
stats sweep using (nsweep = nsweep + 1, 1) nooutput
if (nsweep == 0) { print "error: " . sweep . " is missing or empty (not even a header line)"; exit status 1 }

# the columns by their headers ("name [unit]"), the first line of each CSV
c_scene = "scene"; c_inertia = "flywheel_inertia [kg m^2]"; c_exact = "exact_delta [-]"; c_run = loaded_run . "_delta [-]"
c_rpm = "speed_rpm [rpm]"; c_k = "k [-]"; c_error = "norton_error [-]"
set datafile columnheaders

# the scenes, in order of appearance (at most 6)
array S[6]
nscenes = 0
if (nlines > 1) {
    stats curve using (s = strcol(c_scene), (nscenes == 0 || S[nscenes] ne s) && nscenes < 6 ? (nscenes = nscenes + 1, S[nscenes] = s) : 0, 0) nooutput
}
array C[6] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"]
array R[3] = [1500, 3000, 6000]
array RC[3] = ["#1f77b4", "#2ca02c", "#d62728"]
array RN[3] = [0, 0, 0]  # rows per speed: a speed without rows gets no line (gnuplot refuses an all-undefined plot)
do for [i = 1:3] {
    if (nsweep > 1) { stats sweep using (column(c_rpm) == R[i] ? RN[i] = RN[i] + 1 : 0, 0) nooutput }
}
rightcmd = ""
do for [i = 1:3] {
    if (RN[i] > 0) {
        rightcmd = rightcmd . (strlen(rightcmd) > 0 ? ", " : "") . \
            sprintf("sweep using (column(c_k)):(column(c_rpm) == %d ? 100.0 * column(c_error) : NaN) with linespoints lw 2 pt 7 lc rgb '%s' title '%d rpm'", R[i], RC[i], R[i])
    }
}

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1100,520 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 1100,520 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 1100,520 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    set multiplot layout 1,2 title "Flywheel sizing for a speed fluctuation C (Norton 13.9)" font ",13"
    set grid lc rgb "#dddddd"
    set logscale xy
    set xlabel "flywheel inertia I_f [kg m^2]"
    set ylabel "speed fluctuation delta [-]"
    set key top right font ",9" samplen 2 noenhanced
    if (nscenes == 0) {
        set label 5 "no scene with [gas]" at graph 0.5, graph 0.5 center
        set xrange [1e-3:1]
        set yrange [1e-3:1e-1]
        plot NaN notitle
        unset label 5
        set autoscale xy
    } else {
        if (loaded_run ne "") {
            plot for [i = 1:nscenes] curve using (column(c_inertia)):(strcol(c_scene) eq S[i] ? column(c_exact) : NaN) with lines lw 2 lc rgb C[i] title S[i], \
                 for [i = 1:nscenes] curve using (column(c_inertia)):(strcol(c_scene) eq S[i] && strcol(c_run) ne "" ? column(c_run) : NaN) with points pt 7 ps 0.8 lc rgb C[i] notitle, \
                 0.01 with lines dt 2 lc rgb "#777777" title "C = 0.01", \
                 NaN with points pt 7 lc rgb "#444444" title "the free run (" . loaded_run . ")"
        } else {
            plot for [i = 1:nscenes] curve using (column(c_inertia)):(strcol(c_scene) eq S[i] ? column(c_exact) : NaN) with lines lw 2 lc rgb C[i] title S[i], \
                 0.01 with lines dt 2 lc rgb "#777777" title "C = 0.01"
        }
    }
    unset logscale xy
    set xlabel "cylinders k (inline four-stroke, the base scene's parts, example pressures)"
    set ylabel "Norton's inertia / exact - 1 [%]"
    set xrange [0.5:6.5]
    set key top left font ",9"
    if (strlen(rightcmd) == 0) {
        set label 6 "no engine of the sweep needs a flywheel for C = 0.01" at graph 0.5, graph 0.5 center
        set yrange [-1:1]
        plot NaN notitle
        unset label 6
        set autoscale y
    } else {
        eval "plot " . rightcmd
    }
    unset xrange
    unset multiplot
    unset output
}
