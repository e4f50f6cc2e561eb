"""Checks of frame2d against closed forms (run: python3 -m unittest, from this
folder; tests/scenario/blind_structures.sh runs it)."""
import unittest

import numpy as np

from frame2d import Frame

E, G, RHO = 210e9, 81e9, 7850.0


def column(parts, length=4.0, b=0.3, shear=True, base_spring=None):
    f = Frame()
    a = f.add_node(0, 0)
    t = f.add_node(0, length)
    A, I = b * b, b**4 / 12
    elements, nodes = f.add_member(a, t, parts, E=E, G=G if shear else 0.0, A=A, I=I, rho=RHO)
    f.fixed |= {(a, 0), (a, 1)}
    if base_spring is None:
        f.fixed.add((a, 2))
    else:
        f.springs.append((a, 2, base_spring))
    return f, t, A, I


class FrameTest(unittest.TestCase):
    def test_cantilever_frequencies_euler_bernoulli_limit(self):
        # Slender, no shear deformation: beta_n L of a clamped-free beam.
        f, _, A, I = column(40, length=10.0, b=0.1, shear=False)
        freqs, _ = f.modes(4)
        bending = [x for x in freqs][:3]
        for bl, got in zip((1.8751041, 4.6940911, 7.8547574), bending):
            want = bl**2 / (2 * np.pi * 10.0**2) * np.sqrt(E * I / (RHO * A))
            # Rotary inertia (included here, absent from the closed form) lowers
            # the frequencies of a slender bar by (r / L)^2-order amounts.
            self.assertAlmostEqual(got / want, 1.0, delta=2e-3 * bl)

    def test_tip_deflection_with_shear_is_exact(self):
        # Timoshenko cantilever under a tip load: P L^3 / 3EI + P L / (kappa G A),
        # exact for any mesh.
        for parts in (1, 3):
            f, tip, A, I = column(parts, length=2.0, b=0.5)
            u = f.static({(tip, 0): 1e5})
            want = 1e5 * 2.0**3 / (3 * E * I) + 1e5 * 2.0 / (5 / 6 * G * A)
            self.assertAlmostEqual(u[3 * tip] / want, 1.0, places=9)

    def test_base_rotational_spring(self):
        # Tip deflection adds P L^2 / k_r from the base rotation.
        kr = 3e7
        f, tip, A, I = column(2, length=3.0, b=0.3, shear=False, base_spring=kr)
        u = f.static({(tip, 0): 1e4})
        want = 1e4 * 27 / (3 * E * I) + 1e4 * 9 / kr
        self.assertAlmostEqual(u[3 * tip] / want, 1.0, places=9)

    def test_portal_with_rigid_beam_has_storey_stiffness_24EI_over_h3(self):
        f = Frame()
        h, L, b = 3.5, 6.0, 0.4
        A, I = b * b, b**4 / 12
        n0, n1 = f.add_node(0, 0), f.add_node(L, 0)
        t0, t1 = f.add_node(0, h), f.add_node(L, h)
        for base, top in ((n0, t0), (n1, t1)):
            f.add_member(base, top, 3, E=E, G=0.0, A=1e6 * A, I=I, rho=RHO)
            f.fixed |= {(base, 0), (base, 1), (base, 2)}
        f.add_member(t0, t1, 2, E=E, G=0.0, A=1e6 * A, I=1e6 * I, rho=RHO)
        u = f.static({(t0, 0): 1e5})
        self.assertAlmostEqual(u[3 * t0] / (1e5 * h**3 / (24 * E * I)), 1.0, places=5)

    def test_semi_rigid_joint(self):
        # A cantilever whose clamp is a rotational spring at a hinge node: the
        # same tip deflection as a base spring, P L^3 / 3EI + P L^2 / k_r.
        kr = 2e7
        f = Frame()
        a, t = f.add_node(0, 0), f.add_node(0, 3.0)
        f.fixed |= {(a, 0), (a, 1), (a, 2)}
        h = f.semi_rigid_end(a, kr)
        b = 0.3
        f.add_member(h, t, 3, E=E, G=0.0, A=b * b, I=b**4 / 12, rho=RHO)
        u = f.static({(t, 0): 1e4})
        want = 1e4 * 27 / (3 * E * b**4 / 12) + 1e4 * 9 / kr
        self.assertAlmostEqual(u[3 * t] / want, 1.0, places=9)
        self.assertEqual(u[3 * h], 0.0)  # the hinge node moves with the clamp
        self.assertAlmostEqual(u[3 * h + 2], -1e4 * 3.0 / kr, places=12)  # clockwise

    def test_mass_of_a_rigid_translation(self):
        f = Frame()
        a, b = f.add_node(0, 0), f.add_node(3, 4)  # 5 m, inclined
        f.add_member(a, b, 4, E=E, G=G, A=0.01, I=1e-5, rho=RHO, line_mass=120.0)
        self.assertAlmostEqual(f.total_translational_mass(), (RHO * 0.01 + 120.0) * 5.0, places=6)


if __name__ == "__main__":
    unittest.main()
