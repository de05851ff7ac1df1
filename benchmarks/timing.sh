# Shared by the timing scripts (source it): wall-clock seconds, the median of numbers on stdin
# (whitespace- or newline-separated), and their q-th quantile (0..1) by nearest rank.
now() { date +%s.%N; }
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
quantile() { tr ' ' '\n' | grep -v '^$' | sort -g | awk -v q="$1" '{a[NR] = $1} END {i = int(q * (NR - 1) + 0.5) + 1; print a[i]}'; }
