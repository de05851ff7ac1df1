# Shared by the timing scripts (source it): wall-clock seconds, and the median of numbers on stdin
# (whitespace- or newline-separated).
now() { date +%s.%N; }
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
