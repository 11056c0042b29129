# torsion.gp -- report part `torsion`: torsional vibration, Holzer's constant inertia against the exact crank train.
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'" reports/torsion.gp
#
# Reads  in_dir/torsion.csv, torsion_modes.csv, torsion_resonances.csv and torsion_ratio.csv (validation/src/parts/
#        torsion.cc declares their columns), each column by its header ("speed_rpm [rpm]")
# Writes out_dir/torsion.svg and out_dir/torsion.png
#
# Two rows, three columns. The first two scenes of torsion.csv (in order of appearance) get a column each: top, the
# Campbell diagram (Holzer's natural frequencies as lines with the band from every throw at its lightest to its
# heaviest, the orders as rays f = n rpm / 60, the multiples of the firings per turn bold, the exact steady state's
# peaks filled and Holzer's open); bottom, the peak-to-peak twist of the section that twists most against speed
# (Holzer's sum of every order as a line, the exact steady state as dots). Right column: exact / Holzer - 1 of the
# worst section against speed (log axis: the scenes' speeds may differ by decades), and against the ratio of
# reciprocating to rotating inertia (empty cells of torsion_ratio: no periodic state, drawn as crosses at 0).

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
name = "torsion"
sweep = in_dir . "/torsion.csv"
modes = in_dir . "/torsion_modes.csv"
peaks = in_dir . "/torsion_resonances.csv"
ratio = in_dir . "/torsion_ratio.csv"

reset
set encoding utf8
set datafile separator ","
do for [f in sweep . " " . modes . " " . peaks . " " . ratio] {
    nf = 0
    stats f using (nf = nf + 1, 1) nooutput
    if (nf == 0) { print "error: " . f . " is missing or empty (not even a header line)"; exit status 1 }
}
nsweep = 0
stats sweep using (nsweep = nsweep + 1, 1) nooutput
nmodes = 0
stats modes using (nmodes = nmodes + 1, 1) nooutput
npeaks = 0
stats peaks using (npeaks = npeaks + 1, 1) nooutput
nratio = 0
stats ratio using (nratio = nratio + 1, 1) nooutput
# The counts above include each file's header line; from here on it names the columns.
set datafile columnheaders

# The scenes, in order of appearance (at most 2), their speed range and their first three modes.
array S[2]
nscenes = 0
if (nsweep > 1) {
    stats sweep using (s = strcol("scene"), (nscenes == 0 || S[nscenes] ne s) && nscenes < 2 ? (nscenes = nscenes + 1, S[nscenes] = s) : 0, 0) nooutput
}
array X0[2] = [1e300, 1e300]
array X1[2] = [0, 0]
array F[6]   # mode m of scene s at F[3 (s - 1) + m], Holzer's J_eq; FL, FH: the band
array FL[6]
array FH[6]
array FIRE[2] = [1, 1]
do for [i = 1:6] { F[i] = NaN; FL[i] = NaN; FH[i] = NaN }
do for [s = 1:nscenes] {
    stats sweep using (strcol("scene") eq S[s] ? (v = column("speed_rpm [rpm]"), X0[s] = (v < X0[s] ? v : X0[s]), X1[s] = (v > X1[s] ? v : X1[s])) : 0, 0) nooutput
    if (nmodes > 1) {
        stats modes using (md = column("mode [-]"), strcol("scene") eq S[s] && md <= 3 ? (F[3 * (s - 1) + md] = column("holzer_hz [Hz]"), FL[3 * (s - 1) + md] = column("min_hz [Hz]"), FH[3 * (s - 1) + md] = column("max_hz [Hz]"), FIRE[s] = column("firings_per_turn [-]")) : 0, 0) nooutput
    }
}
array C[2] = ["#1f77b4", "#d62728"]

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 1500,900 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 1500,900 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 1500,900 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    set multiplot layout 2,3 title "Torsional vibration of the crank train: Holzer's constant inertia against the exact steady state" font ",13"
    set grid lc rgb "#dddddd"
    set key top left font ",9" samplen 2 noenhanced box opaque

    # Row 1, columns 1-2: the Campbell diagrams.
    do for [s = 1:2] {
        if (s > nscenes) {
            set label 5 "no scene with [crankshaft]" at graph 0.5, graph 0.5 center
            set xrange [0:1]
            set yrange [0:1]
            plot NaN notitle
            unset label 5
        } else {
            b = 3 * (s - 1)
            top = (F[b + 2] == F[b + 2] ? 1.25 * F[b + 2] : 2.5 * F[b + 1])
            set title "Campbell diagram: " . S[s] noenhanced
            set xlabel "engine speed [rpm]"
            set ylabel "frequency [Hz]"
            set xrange [0:1.05 * X1[s]]
            set yrange [0:top]
            do for [m = 1:3] {
                if (FL[b + m] == FL[b + m]) {
                    set object m rectangle from graph 0, first FL[b + m] to graph 1, first FH[b + m] fc rgb "#f2c6a0" fs solid 0.5 noborder behind
                }
            }
            # The peaks' series only where the scene has some (a series without points would warn).
            nexact = 0
            nholzer = 0
            if (npeaks > 1) {
                stats peaks using (strcol("scene") eq S[s] ? (strcol("route") eq "exact" ? nexact = nexact + 1 : (nholzer = nholzer + 1)) : 0, 0) nooutput
            }
            cmd = "for [n = 1:24] (n * x / 60.0 < top ? n * x / 60.0 : NaN) with lines lw (n % int(FIRE[s]) == 0 ? 2 : 0.5) " . \
                  "lc rgb (n % int(FIRE[s]) == 0 ? '#555555' : '#bbbbbb') notitle, " . \
                  "F[b + 1] with lines lw 2 lc rgb '#ff7f0e' title \"Holzer's modes (band: J min .. J max)\", " . \
                  "for [m = 2:3] (F[b + m] == F[b + m] ? F[b + m] : NaN) with lines lw 2 lc rgb '#ff7f0e' notitle"
            if (nexact > 0) {
                cmd = cmd . ", peaks using (strcol('scene') eq S[s] && strcol('route') eq 'exact' ? column('speed_rpm [rpm]') : NaN):'frequency_hz [Hz]' with points pt 7 ps 1.3 lc rgb '#d62728' title \"exact steady state's peaks\""
            }
            if (nholzer > 0) {
                cmd = cmd . ", peaks using (strcol('scene') eq S[s] && strcol('route') eq 'holzer' ? column('speed_rpm [rpm]') : NaN):'frequency_hz [Hz]' with points pt 6 ps 1.8 lc rgb '#1f77b4' title \"Holzer's peaks\""
            }
            eval "plot " . cmd
            do for [m = 1:3] { unset object m }
            unset title
        }
    }

    # Row 1, column 3: exact / Holzer - 1 against speed.
    set title "exact / Holzer - 1, worst section"
    set xlabel "engine speed [rpm]"
    set ylabel "[%]"
    set logscale x
    set autoscale xy
    set offsets 0, 0, graph 0.08, graph 0.08
    if (nscenes == 0) {
        set xrange [1:10]
        plot NaN notitle
    } else {
        plot for [s = 1:nscenes] sweep using (strcol("scene") eq S[s] ? column("speed_rpm [rpm]") : NaN):(100.0 * column("worst_difference [-]")) with linespoints lw 2 pt 7 ps 0.6 lc rgb C[s] title S[s], \
             10 with lines dt 2 lc rgb "#999999" title "+-10 %", -10 with lines dt 2 lc rgb "#999999" notitle, \
             0 with lines lc rgb "#444444" notitle
    }
    unset logscale x
    unset offsets
    unset title

    # Row 2, columns 1-2: the twist against speed.
    do for [s = 1:2] {
        if (s > nscenes) {
            set xrange [0:1]
            set yrange [0:1]
            plot NaN notitle
        } else {
            set title "peak-to-peak twist: " . S[s] noenhanced
            set xlabel "engine speed [rpm]"
            set ylabel "twist of the section that twists most [rad]"
            set xrange [0:1.05 * X1[s]]
            set autoscale y
            set yrange [0:*]
            plot sweep using (strcol("scene") eq S[s] ? column("speed_rpm [rpm]") : NaN):"holzer [rad]" with lines lw 2 lc rgb "#1f77b4" title "Holzer, every order", \
                 sweep using (strcol("scene") eq S[s] ? column("speed_rpm [rpm]") : NaN):"holzer_order24 [rad]" with lines lw 1 dt 2 lc rgb "#1f77b4" title "Holzer, orders <= 24", \
                 sweep using (strcol("scene") eq S[s] ? column("speed_rpm [rpm]") : NaN):"exact [rad]" with linespoints lw 1 pt 7 ps 0.7 lc rgb "#d62728" title "exact steady state"
            unset title
        }
    }

    # Row 2, column 3: the ratio sweep.
    set title "exact / Holzer - 1 at the major order's critical speed"
    set xlabel "reciprocating / rotating inertia [-]"
    set ylabel "[%]"
    set logscale x
    set autoscale xy
    if (nratio <= 1) {
        set label 6 "no ratio sweep" at graph 0.5, graph 0.5 center
        set xrange [0.1:10]
        plot NaN notitle
        unset label 6
    } else {
        # A row without a periodic state has exact and worst_difference empty; the test reads exact: for an empty last
        # field gnuplot 5.4's strcol returns a stale string.
        nbroken = 0
        stats ratio using (strcol("exact [rad]") eq "" ? nbroken = nbroken + 1 : 0, 0) nooutput
        cmd = "ratio using 'ratio [-]':(strcol('worst_difference [-]') ne '' ? 100.0 * column('worst_difference [-]') : NaN) with linespoints lw 2 pt 7 lc rgb '#2ca02c' title 'worst section', " . \
              "10 with lines dt 2 lc rgb '#999999' title '+-10 %', -10 with lines dt 2 lc rgb '#999999' notitle"
        if (nbroken > 0) {
            cmd = cmd . ", ratio using 'ratio [-]':(strcol('exact [rad]') eq '' ? 0 : NaN) with points pt 2 ps 2 lc rgb '#000000' title 'no periodic state'"
        }
        eval "plot " . cmd
    }
    unset logscale x
    unset title
    unset multiplot
    unset output
}
