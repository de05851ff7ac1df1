#!/bin/sh
# Writes the built-in machines' SimGrid platforms, ipsc1.xml and cluster.xml, beside this script. They are
# data a user may copy and change (--platform FILE.xml); this script only saves writing a few thousand
# routes by hand. Run it again after changing a number below, and commit what it writes.
set -eu
cd "$(dirname "$0")"

# The iPSC/1's largest machine, a 7-cube (128 nodes): node speed, and its links (machines-and-engines.md:
# 10 Mbit/s Ethernet-chip links, about 1 ms to a neighbour and 1 ms more per further hop, mostly software).
ipsc1_nodes=128
# The node speed is the one fitted constant (README, "Emulated machine time"): the speed that makes one
# processor render the paper's table-2 case (balls 2, 128x128, depth 5) in 13941 s with ipsc1.costs, fitted
# with `raycube scaling --size 128x128 --emulate ipsc1 --light-rays messages --load-metric rays --procs 1
# --fit 13941`.
ipsc1_speed=2138.8f
# The wire: a 128-byte ray at 0.56 MB/s (1.8 us per byte: Nugent 1988's "ten times the bandwidth of the
# iPSC/1" against the iPSC/2's 5.6 MB/s full duplex; 0.28 MB/s if it compares one direction) and one minimum
# Ethernet frame's time (64 bytes at 10 Mbit/s) of latency; the software overheads, most of the iPSC/1's
# millisecond to a neighbour, are charged on the CPUs in ipsc1.costs.
ipsc1_bandwidth=560kBps
ipsc1_latency=51.2us
# A present-day cluster of up to 4096 nodes: the cost table's flop-equivalents per second one core of this
# host achieves on balls 2, measured by benchmarks/cluster_calibration_benchmark.cpp (node_speed; README,
# "On a present-day cluster") and copied here by hand; links of about 1 us and 10 GB/s through a switch.
cluster_nodes=4096
cluster_speed=400Mf
cluster_bandwidth=10GBps
cluster_latency=1us
cluster_nic_latency=0.5us  # half the latency each side of the switch

header() {
  cat <<XML
<?xml version='1.0'?>
<!DOCTYPE platform SYSTEM "https://simgrid.org/simgrid.dtd">
<!-- Written by host/machine/platforms/generate.sh (which says where each number comes from): $1 -->
<platform version="4.1">
XML
}

# Hosts node-0 ... node-<n-1> and manager (the cube manager, the host process's end).
hosts() {
  awk -v n="$1" -v speed="$2" 'BEGIN {
    for (i = 0; i < n; ++i) printf "    <host id=\"node-%d\" speed=\"%s\"/>\n", i, speed
    printf "    <host id=\"manager\" speed=\"%s\"/>\n", speed }'
}

# Every node's own link to the manager (the iPSC's eighth port). The manager receives the nodes'
# contributions on it during the synthesis; on the iPSC/1 it also sends each node its setup over it before
# (3.2 step 1): symmetrical routes (YES). Where routes are searched (Dijkstra), a symmetrical link would make
# the manager a way between nodes: the cluster's manager sends through the switch instead (NO).
manager_links() {
  awk -v n="$1" -v bw="$2" -v lat="$3" 'BEGIN {
    for (i = 0; i < n; ++i)
      printf "    <link id=\"node-%d:manager\" bandwidth=\"%s\" latency=\"%s\"/>\n", i, bw, lat }'
}
manager_routes() {
  awk -v n="$1" -v both="$2" 'BEGIN {
    for (i = 0; i < n; ++i)
      printf "    <route src=\"node-%d\" dst=\"manager\" symmetrical=\"%s\"><link_ctn id=\"node-%d:manager\"/></route>\n", i, both, i }'
}

{
  header "the Intel iPSC/1 (Priol & Bouatouch's machine), store and forward"
  cat <<XML
  <!-- A link per direction between hypercube neighbours (the iPSC's seven ports): a message to a
       non-neighbour is relayed by the nodes' communication tasks (routing store-and-forward in
       ipsc1.costs), so only neighbours have routes. -->
  <zone id="machine" routing="Full">
XML
  hosts $ipsc1_nodes $ipsc1_speed
  manager_links $ipsc1_nodes $ipsc1_bandwidth $ipsc1_latency
  awk -v n=$ipsc1_nodes -v bw=$ipsc1_bandwidth -v lat=$ipsc1_latency 'BEGIN {
    for (i = 0; i < n; ++i)
      for (bit = 1; bit < n; bit *= 2)
        printf "    <link id=\"node-%d:node-%d\" bandwidth=\"%s\" latency=\"%s\"/>\n", i, (int(i / bit) % 2 ? i - bit : i + bit), bw, lat }'
  manager_routes $ipsc1_nodes YES
  awk -v n=$ipsc1_nodes 'BEGIN {
    for (i = 0; i < n; ++i)
      for (bit = 1; bit < n; bit *= 2)
        printf "    <route src=\"node-%d\" dst=\"node-%d\" symmetrical=\"NO\"><link_ctn id=\"node-%d:node-%d\"/></route>\n", i, (int(i / bit) % 2 ? i - bit : i + bit), i, (int(i / bit) % 2 ? i - bit : i + bit) }'
  echo '  </zone>'
  echo '</platform>'
} > ipsc1.xml

{
  header "a present-day cluster, direct routing through a switch"
  cat <<XML
  <!-- Each node has one network interface into the switch: a message crosses the sender's and the
       receiver's (Dijkstra finds that route for any two nodes; routing direct in cluster.costs). -->
  <zone id="machine" routing="DijkstraCache">
XML
  hosts $cluster_nodes $cluster_speed
  echo '    <router id="switch"/>'
  manager_links $cluster_nodes $cluster_bandwidth $cluster_latency
  awk -v n=$cluster_nodes -v bw=$cluster_bandwidth -v lat=$cluster_nic_latency 'BEGIN {
    for (i = 0; i < n; ++i) printf "    <link id=\"node-%d:nic\" bandwidth=\"%s\" latency=\"%s\"/>\n", i, bw, lat }'
  # The manager's own interface into the switch, for the setups it sends.
  echo "    <link id=\"manager:nic\" bandwidth=\"$cluster_bandwidth\" latency=\"$cluster_nic_latency\"/>"
  manager_routes $cluster_nodes NO
  echo '    <route src="manager" dst="switch" symmetrical="NO"><link_ctn id="manager:nic"/></route>'
  awk -v n=$cluster_nodes 'BEGIN {
    for (i = 0; i < n; ++i)
      printf "    <route src=\"node-%d\" dst=\"switch\"><link_ctn id=\"node-%d:nic\"/></route>\n", i, i }'
  echo '  </zone>'
  echo '</platform>'
} > cluster.xml
