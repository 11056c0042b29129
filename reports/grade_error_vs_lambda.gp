# grade_error_vs_lambda.gp -- a graded program's error against lambda = r / l (crankcheck grade).
#
#   gnuplot -e "in_dir='DIR'; out_dir='DIR'; quantities='U Q a_p'" reports/grade_error_vs_lambda.gp
#
# Reads  in_dir/grade_error_vs_lambda.csv   (validation/grade.h: GradeLambdaRow), its columns by header name
# Writes out_dir/grade_error_vs_lambda.svg and out_dir/grade_error_vs_lambda.png
#
# One coloured line per provided quantity (the program's largest error against Simbody at that lambda, relative
# to the quantity's scale); in black the analytic engine's own largest error over the same quantities; dashed,
# the gate's tolerance 64 eps x conditioning at each lambda. Errors of 0 are drawn at 1e-17.

if (!exists("in_dir"))  in_dir  = "."
if (!exists("out_dir")) out_dir = "."
if (!exists("quantities")) quantities = "U Q drive_torque x_p v_p a_p"
name = "grade_error_vs_lambda"
file = in_dir . "/" . name . ".csv"

reset
set encoding utf8
set datafile separator ","
set datafile columnheaders
floor = 1e-17
clamp(v) = (v < floor) ? floor : v
eps = 2.220446049250313e-16
# The conditioning of the comparison (scales.h): 1 / (1 - lambda^2) x (l + r) / r = (1 + lambda) / (lambda (1 - lambda^2)).
tolerance(l) = 64 * eps * (1 + l) / (l * (1 - l * l))

set logscale xy
set format y "10^{%L}"
set xlabel "lambda = r / l"
set ylabel "largest error / scale [-]"
set key outside right top
set grid
set yrange [1e-17:*]

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) { pngterm = "pngcairo" } else { pngterm = "png" }
do for [fmt in "svg png"] {
    if (fmt eq "svg") {
        set terminal svg size 900,520 enhanced font "DejaVu Sans,10" background rgb "white"
    } else {
        if (pngterm eq "pngcairo") {
            set terminal pngcairo size 900,520 enhanced font "DejaVu Sans,10" background rgb "white"
        } else {
            set terminal png size 900,520 enhanced font "DejaVuSans,10" background rgb "white"
        }
    }
    set output out_dir . "/" . name . "." . fmt
    plot for [q in quantities] file using "lambda [-]":(strcol("quantity") eq q ? clamp(column("program_max_rel_error [-]")) : NaN) \
             with linespoints lw 2 title q, \
         file using "lambda [-]":(clamp(column("analytic_max_rel_error [-]"))) with points pt 7 ps 0.6 lc rgb "black" title "analytic engine", \
         tolerance(x) with lines dt 2 lc rgb "gray40" title "tolerance"
    unset output
}
