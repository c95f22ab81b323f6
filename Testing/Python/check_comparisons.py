"""Checks the numbers of the paper comparisons (Examples/paper_comparisons.py --quick) against
the paper's claims and against bounds derived next to each check (discretization errors,
closed-form values).

    python3 check_comparisons.py OUTPUT_DIR
"""
import csv
import math
import os
import sys

out_dir = sys.argv[1]
failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what)
    if not condition:
        failures.append(what)


def rows(name):
    with open(os.path.join(out_dir, name)) as f:
        return list(csv.DictReader(f))


# Fig. 3: deviation from the shell, relative to the handle displacement
fig3 = {(r['energy'], r['basis']): (float(r['rms_deviation']), float(r['max_deviation'])) for r in rows('fig3_deviation.csv')}
bases = ['MLS s=5', 'Wendland s=5', 'Wendland s=50', 'Gaussian s=5', 'Gaussian s=50', 'Biharmonic', 'Triharmonic']
check(all((e, b) in fig3 for e in ('bending', 'stretching') for b in bases), 'Fig. 3: every basis, bending and stretching')
# a requirement, not a derived bound: the paper's claim that MLS with s = 5 matches the surface
# deformation ("high quality results already with a cover of s = 5", section 4), read as the
# comparisons' 2% RMS target (plotted by Examples/paper_comparisons.py); the discretization bound
# below is far tighter
check(fig3[('bending', 'MLS s=5')][0] < 0.02, 'Fig. 3 target: MLS s=5 bending within 2%% RMS (%.5f)' % fig3[('bending', 'MLS s=5')][0])
# Discretization errors of the k = 1000 MLS subspace on the unit plane (sample spacing
# h = 1 / sqrt(1000) = 0.032, support radius r = sqrt(5 / (1000 pi)) = 0.04 at cover 5), in units
# of the lift over the free length 0.8:
# - bending: about a clamped cubic, |z''| <= 6 / 0.8^2 = 9.4; a scheme that reproduces linear
#   functions misses it by h^2 |z''| / 8 (linear interpolation's constant) = 1.2e-3;
# - stretching: the shell's profile kinks at both strips by the slope 1 / 0.8, which a smooth
#   subspace rounds over its support radius: (1 / 0.8) r / 8 = 6e-3 along the two kink lines, on
#   about 2 x 2r = 16% of the plane: an RMS of 6e-3 x sqrt(0.16) = 2.5e-3.
check(fig3[('bending', 'MLS s=5')][0] < 1.2e-3,
      'Fig. 3: MLS s=5 bending RMS within its O(h^2) discretization error 1.2e-3 (%.2e)' % fig3[('bending', 'MLS s=5')][0])
check(fig3[('stretching', 'MLS s=5')][0] < 2.5e-3,
      'Fig. 3: MLS s=5 stretching RMS within the rounding of the kinks, 2.5e-3 (%.2e)' % fig3[('stretching', 'MLS s=5')][0])
# Requirements of the paper's claims, read as factors: compact RBFs with s = 5 show artifacts
# ("a small radius of s = 5 leads to artifacts", section 4: read as twice the largest deviation of
# MLS), triharmonic RBFs fail at stretching ("they fail to model stretching-dominant materials":
# read as an order of magnitude worse). The second is also what the kink rounding above predicts:
# a globally smooth basis rounds the kinks over the free length 0.8 instead of the support radius
# 0.04, 20 times more.
for basis in ('Wendland s=5', 'Gaussian s=5'):
    check(fig3[('bending', basis)][1] > 2 * fig3[('bending', 'MLS s=5')][1],
          'Fig. 3: %s deviates more than MLS s=5 (max %.5f vs %.5f)' % (basis, fig3[('bending', basis)][1], fig3[('bending', 'MLS s=5')][1]))
check(fig3[('stretching', 'Triharmonic')][0] > 10 * fig3[('stretching', 'MLS s=5')][0],
      'Fig. 3: triharmonic RBFs miss stretching (RMS %.4f vs MLS %.4f)' % (fig3[('stretching', 'Triharmonic')][0], fig3[('stretching', 'MLS s=5')][0]))
# a written plot: an empty 110-dpi figure compresses to a few kB, one with its curves or images to more
check(os.path.getsize(os.path.join(out_dir, 'fig3_mean_curvature.png')) > 10000, 'Fig. 3: mean-curvature image written')

# Fig. 4: time and memory
fig4 = {(r['basis'], int(r['k'])): (float(r['setup_seconds']), float(r['memory_mib'])) for r in rows('fig4_performance.csv')}
check(fig4[('MLS s=5', 1000)][0] < fig4[('Biharmonic', 1000)][0] and fig4[('MLS s=5', 1000)][0] < fig4[('Wendland s=50', 1000)][0],
      'Fig. 4: MLS s=5 sets up faster than Biharmonic and Wendland s=50 at k = 1000')
# a requirement: the paper's Fig. 4 claim that global RBFs' dense matrices need more memory than the
# compact MLS system, read as "less than half"
check(fig4[('MLS s=5', 1000)][1] < 0.5 * fig4[('Biharmonic', 1000)][1] and fig4[('MLS s=5', 1000)][1] < 0.5 * fig4[('Wendland s=50', 1000)][1],
      'Fig. 4: MLS s=5 needs less than half their memory at k = 1000 (%.0f MiB)' % fig4[('MLS s=5', 1000)][1])
# linear growth doubles the memory from k = 1000 to 2000, the dense bases' quadratic growth would
# quadruple it: below 4x (plus 50 MiB for allocator and timing noise of a small process)
check(fig4[('MLS s=5', 2000)][1] < 4 * fig4[('MLS s=5', 1000)][1] + 50, 'Fig. 4: MLS memory grows about linearly in k')
check(os.path.getsize(os.path.join(out_dir, 'fig4_performance.png')) > 10000, 'Fig. 4: plot written')

# Fig. 12: no inversion, MLS at least as good as triharmonic
fig12 = {r['method']: r for r in rows('fig12_sphere_hole.csv')}
for method in ('MLS s=5', 'Triharmonic'):
    check(int(fig12[method]['inverted_after']) == 0 and float(fig12[method]['min_scaled_jacobian_after']) > 0,
          'Fig. 12 target: %s inverts no element (min scaled Jacobian %.3f)' % (method, float(fig12[method]['min_scaled_jacobian_after'])))
check(float(fig12['MLS s=5']['min_scaled_jacobian_after']) >= float(fig12['Triharmonic']['min_scaled_jacobian_after']),
      'Fig. 12 target: MLS min scaled Jacobian at least the triharmonic one')
# the paper's Fig. 12 figures: MLS keeps 0.05 of the original 0.12 (was half of it, which the paper
# does not claim)
check(float(fig12['MLS s=5']['min_scaled_jacobian_after']) > 0.05 / 0.12 * float(fig12['MLS s=5']['min_scaled_jacobian_before']),
      'Fig. 12: MLS keeps at least the paper\'s fraction 0.05 / 0.12 of the original min scaled Jacobian (recorded: all of it)')

# Fig. 13: the hexahedral pipe
fig13 = rows('fig13_hex_pipe.csv')[0]
# the generated pipe's hexahedra have corner angles of 90 - 180 / 24 degrees (24 around): their
# scaled Jacobian is cos(pi / 24) = 0.99144, up to the round-off of a few dozen operations
check(abs(float(fig13['min_scaled_jacobian_before']) - math.cos(math.pi / 24)) < 1e-12,
      'Fig. 13: the generated pipe (min scaled Jacobian cos(pi / 24) = 0.99144)')
# The pipe (length 6, Examples/paper_comparisons.py) is bent into an S: its top moves by 1.5 with
# the end sections parallel. The worst case for a cell is pure shear (its section translated
# without turning) at the largest slope of the smoothest such profile, the cubic with zero end
# slopes: 1.5 x 1.5 / 6 = 0.375; a shear of slope t scales the scaled Jacobian by cos(atan t).
shear = 1 / math.sqrt(1 + (1.5 * 1.5 / 6) ** 2)
check(int(fig13['inverted_after']) == 0 and float(fig13['min_scaled_jacobian_after']) >= shear * float(fig13['min_scaled_jacobian_before']),
      'Fig. 13: bent pipe keeps min scaled Jacobian >= cos(atan 0.375) x before = %.3f (%.3f, recorded 0.962)' % (
          shear * float(fig13['min_scaled_jacobian_before']), float(fig13['min_scaled_jacobian_after'])))
with open(os.path.join(out_dir, 'report.md')) as f:
    report = f.read()
check(all('## Fig. %d' % n in report for n in (3, 4, 12, 13)), 'report.md has the four sections')

print('failed: %s' % failures if failures else 'all checks passed')
sys.exit(1 if failures else 0)
