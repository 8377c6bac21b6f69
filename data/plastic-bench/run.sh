#!/bin/sh
# The hardness cap beside ContactMechanics, one thread each: 512^2 and 1024^2, H = 0.1 E*,
# mean pressure 0.03 E*. Needs `roughcontact` on the PATH and a virtualenv with
# ContactMechanics (`pip install ContactMechanics SurfaceTopography numpy`) as $CM_PYTHON.
set -e
for n in 512 1024; do
  cutoff=$(python3 -c "print(8/$n)")
  roughcontact generate --n $n --length 1 --rolloff 1 --cutoff $cutoff --rms-gradient 1 --seed 2026 \
      --no-png --output surface-$n.npy > /dev/null
  # The same surface: iterations, time and the cells off a 1e-12 solve; that solve's fields
  # for ContactMechanics' accuracy.
  roughcontact bench --sizes $n --threads 1 --hardness 0.1 --pressure 0.03 --check --solver preconditioned
  roughcontact solve --surface surface-$n.npy --length 1 --modulus 1 --hardness 0.1 \
      --mean-pressure 0.03 --tolerance 1e-12 --no-png --overwrite --out ours-$n-1e-12 > /dev/null
  OMP_NUM_THREADS=1 $CM_PYTHON cm_bench.py surface-$n.npy 0.1 0.03
done
