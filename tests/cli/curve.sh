# CLI: rg2 --version/--help and rg2 curve, including bad input.
. "$(dirname "$0")/lib.sh"
expect 0 "rg2 0." -- "$RG2" --version
expect 0 "commands:" -- "$RG2" --help
expect 2 "unknown command" -- "$RG2" frobnicate
expect 0 "usage: rg2 curve" -- "$RG2" curve --help
expect 0 "4 rational cubic Bezier segments" -- "$RG2" curve --arcs 4
expect 0 '"segments"' -- "$RG2" curve --arcs 5 --radius 2 --json
expect 0 "3 rational cubic Bezier segments" -- "$RG2" curve --angles 100,120,140
expect 1 "arc 1 has opening angle" -- "$RG2" curve --angles 100,180,80
expect 1 "sum to 2 pi" -- "$RG2" curve --angles 100,100,100
expect 2 "not a finite number" -- "$RG2" curve --angles 100,abc,80
expect 0 "2 rational cubic Bezier segments" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2"
expect 1 "w[1] = -1" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --w 1,1,-1,1,1,1
expect 1 "junction 2 has K" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --g 0,0,-9,0,0
expect 2 "need 6 weights" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --w 1,1
expect 2 "unknown option" -- "$RG2" curve --bogus
# the JSON output is exact: the 90-degree circle's middle weight (1 + 2 cos 45)/3
"$RG2" curve --arcs 4 --json | grep -q '0.80473785412436' && ok || bad "exact circle weight"
finish
