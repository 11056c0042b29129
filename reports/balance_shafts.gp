# balance_shafts.gp -- report part `balance_shafts`: what designed balance shafts cancel, by every exact engine.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/balance_shafts.gp
#
# Reads  in_dir/balance_shafts.csv (columns by their header names, validation/src/parts/balance_shafts.cc)
# Writes out_dir/balance_shafts.svg and out_dir/balance_shafts.png
#
# One panel per case (at most 3): the amplitude of harmonic n of the shaking force relative to the force scale (log y,
# exact zeros and amplitudes below 1e-17 drawn at 1e-17), without shafts (grey, the closed form) and with them (the
# closed form as a blue line, Simbody's DFT as red dots, MuJoCo's as green circles). Each series' rows come together,
# in order of n (crankcheck sorts the tables by their first columns).

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "balance_shafts"
data = in_dir . "/balance_shafts.csv"

reset
set encoding utf8
set datafile separator ","
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
nlines = 0
stats data using (nlines = nlines + 1, 1) nooutput
if (nlines == 0) { print "error: " . data . " is missing or empty (not even a header line)"; exit status 1 }
set datafile columnheaders

# the cases, in order of appearance (at most 3)
array S[3]
ncases = 0
if (nlines > 1) {
    stats data using (s = strcol("case"), (ncases == 0 || S[ncases] ne s) && ncases < 3 ? (ncases = ncases + 1, S[ncases] = s) : 0, 0) nooutput
}
panels = (ncases > 0) ? ncases : 1

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1200,480 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 1200,480 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 1200,480 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    set multiplot layout 1,panels title "Balance shafts: the shaking force's harmonics without and with a designed set" font ",13"
    set grid lc rgb "#dddddd"
    set logscale y
    set format y "10^{%T}"
    set yrange [floor / 3 : 1e4]
    set xrange [0.5:6.5]
    set xtics 1
    set xlabel "harmonic n"
    set ylabel "amplitude / force scale [-]"
    set key top right font ",9" samplen 2 noenhanced
    if (ncases == 0) {
        set label 5 "no case" at graph 0.5, graph 0.5 center
        plot NaN notitle
        unset label 5
    } else {
        do for [i = 1:ncases] {
            set title S[i] noenhanced font ",10"
            plot data using "n [-]":(strcol("case") eq S[i] && strcol("shafts") eq "none" && strcol("engine") eq "analytic" ? clamp(column("force_relative [-]")) : NaN) \
                     with linespoints lw 4 pt 5 ps 0.9 lc rgb "#bbbbbb" title "without shafts", \
                 data using "n [-]":(strcol("case") eq S[i] && strcol("shafts") eq "with" && strcol("engine") eq "analytic" ? clamp(column("force_relative [-]")) : NaN) \
                     with lines lw 2 lc rgb "#1f77b4" title "with: closed form", \
                 data using "n [-]":(strcol("case") eq S[i] && strcol("shafts") eq "with" && strcol("engine") eq "simbody" ? clamp(column("force_relative [-]")) : NaN) \
                     with points pt 7 ps 0.8 lc rgb "#d62728" title "with: Simbody (DFT)", \
                 data using "n [-]":(strcol("case") eq S[i] && strcol("shafts") eq "with" && strcol("engine") eq "mujoco" ? clamp(column("force_relative [-]")) : NaN) \
                     with points pt 6 ps 1.3 lc rgb "#2ca02c" title "with: MuJoCo (DFT)"
        }
    }
    unset multiplot
    unset output
}
