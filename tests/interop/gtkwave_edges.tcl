# Prints "edges NAME RISING FALLING" for every signal GTKWave loaded, then quits.
# Run as: xvfb-run -a gtkwave -S gtkwave_edges.tcl FILE.vcd
set n [gtkwave::getNumFacs]
for {set i 0} {$i < $n} {incr i} {
  set name [gtkwave::getFacName $i]
  set rising 0
  set falling 0
  set last ""
  foreach {t v} [gtkwave::signalChangeList $name -max 100000000] {
    if {$last eq "0" && $v eq "1"} { incr rising }
    if {$last eq "1" && $v eq "0"} { incr falling }
    set last $v
  }
  puts "edges $name $rising $falling"
}
gtkwave::/File/Quit
