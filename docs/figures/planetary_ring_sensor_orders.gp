# The ring-housing sensor of examples/planetary_stage_cracked_sun.toml, healthy (its [[faults]]
# deleted) and with its cracked sun tooth: the order spectra of `gearimpact signals` on the
# carrier's angle (docs/planetary.md, "The ring sensor's spectrum with gearimpact signals").
set datafile separator ','
set terminal pngcairo size 1000,700 font 'Sans,11'
set output 'planetary_ring_sensor_orders.png'
set multiplot layout 2,1
set logscale y
set format y '10^{%L}'
set yrange [1e-12:1e3]
set xrange [0:330]
set xtics 30
set grid
set ylabel 'amplitude (N)'
on(x)  = (abs(x - floor(x + 0.5)) < 1e-9 && int(floor(x + 0.5)) % 3 == 0)
set key outside top right horizontal
set title 'ring sensor, healthy stage (21/30/81, N = 3): one carrier turn, rectangular window'
plot 'healthy.csv' using 1:(on($1) ? $2 : NaN) every ::1 with impulses lw 2 lc rgb '#1f4e99' title 'multiples of N = 3 carrier orders', \
     '' using 1:(on($1) ? NaN : $2) every ::1 with impulses lw 1 lc rgb '#c0392b' title 'other orders'
set title 'ring sensor, sun tooth 0 root-cracked (1 mm deep at 45 deg): lines between the comb lines'
set xlabel 'carrier order (cycles per carrier turn)'
plot 'cracked.csv' using 1:(on($1) ? $2 : NaN) every ::1 with impulses lw 2 lc rgb '#1f4e99' title 'multiples of N = 3 carrier orders', \
     '' using 1:(on($1) ? NaN : $2) every ::1 with impulses lw 1 lc rgb '#c0392b' title 'other orders'
unset multiplot
