"""Checks of frame3d against closed forms and against frame2d (run: python3 -m
unittest test_frame3d, from this folder, as test_frame2d)."""
import unittest

import numpy as np

import frame2d
import frame3d
from frame3d import Frame3d, UX, UY, UZ, RX, RY, RZ

E, G, RHO = 210e9, 81e9, 7850.0
SKEW = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
DIRECTIONS = {"x": (1.0, 0, 0), "y": (0, 1.0, 0), "z": (0, 0, 1.0), "skew": tuple(SKEW)}
BETA_L = (1.8751041, 4.6940911)

# A slender bar with unequal principal moments (L / r > 200 in both planes).
BAR = dict(A=0.01, Iy=2e-5, Iz=8e-6, J=1.2e-5, Ip=2.8e-5)


def cantilever(direction, parts, length, section, ref=None, **props):
    """A member from the origin along `direction`, clamped at the origin."""
    f = Frame3d()
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    a = f.add_node(0, 0, 0)
    t = f.add_node(*(length * d))
    kw = dict(E=E, G=G, rho=RHO, ref=ref)
    kw.update(section)
    kw.update(props)
    _, nodes = f.add_member(a, t, parts, **kw)
    f.fix(a)
    return f, t, nodes


def first(freqs, kinds, kind):
    """The lowest frequency whose mode is more than 99 % of `kind`."""
    return next(fr for fr, k in zip(freqs, kinds) if k[kind] > 0.99)


def classify(f, shapes, nodes, ref=None):
    """For each mode, the share of its nodal translations along local x, y, z
    and of its rotations about local x (torsion), over the member's nodes."""
    _, R = frame3d.local_axes(f.xyz[nodes[0]], f.xyz[nodes[-1]], ref)
    idx = np.array(nodes)
    out = []
    for k in range(shapes.shape[1]):
        u = np.stack([shapes[6 * idx + i, k] for i in range(3)], axis=1) @ R.T
        r = np.stack([shapes[6 * idx + 3 + i, k] for i in range(3)], axis=1) @ R.T
        tr = (u**2).sum(axis=0)
        n = max(tr.sum(), 1e-300)  # a pure torsion mode has no translation
        out.append(dict(x=tr[0] / n, y=tr[1] / n, z=tr[2] / n,
                        torsion=(r[:, 0] ** 2).sum() / max((r**2).sum(), 1e-300)))
    return out


class ElementTest(unittest.TestCase):
    def test_timoshenko_matrices_from_the_exact_static_shapes(self):
        # Przemieniecki's phi-dependent shape functions (the exact deflection v
        # and section rotation psi of a shear-deformable member under end
        # loads): the coded closed forms must equal int m N'N dx, int rho I
        # Npsi'Npsi dx and int EI psi'^2 + kappa G A (v' - psi)^2 dx. Gauss
        # quadrature with 6 points is exact for these degree <= 6 polynomials,
        # so agreement to rounding (1e-12) is expected.
        L, EI, kGA, m, rI = 2.3, 5.0e7, 3.0e8, 310.0, 0.7
        phi = 12 * EI / (kGA * L * L)
        g, w = np.polynomial.legendre.leggauss(6)
        xi, w = (g + 1) / 2, w / 2
        c = 1 / (1 + phi)
        Nv = c * np.array([2 * xi**3 - 3 * xi**2 - phi * xi + 1 + phi,
                           L * (xi**3 - (2 + phi / 2) * xi**2 + (1 + phi / 2) * xi),
                           -2 * xi**3 + 3 * xi**2 + phi * xi,
                           L * (xi**3 - (1 - phi / 2) * xi**2 - phi / 2 * xi)])
        dNv = c * np.array([6 * xi**2 - 6 * xi - phi,
                            L * (3 * xi**2 - (4 + phi) * xi + 1 + phi / 2),
                            -6 * xi**2 + 6 * xi + phi,
                            L * (3 * xi**2 - (2 - phi) * xi - phi / 2)]) / L
        Np = c * np.array([6 * (xi**2 - xi) / L, 3 * xi**2 - (4 + phi) * xi + 1 + phi,
                           -6 * (xi**2 - xi) / L, 3 * xi**2 - (2 - phi) * xi])
        dNp = c * np.array([6 * (2 * xi - 1) / L, 6 * xi - (4 + phi), -6 * (2 * xi - 1) / L,
                            6 * xi - (2 - phi)]) / L
        mt = L * (Nv * w) @ Nv.T * m
        mr = L * (Np * w) @ Np.T * rI
        k = L * ((dNp * w) @ dNp.T * EI + ((dNv - Np) * w) @ (dNv - Np).T * kGA)
        got_t, got_r = frame3d._bending_mass(m, rI, phi, L, "timoshenko")
        np.testing.assert_allclose(got_t, mt, rtol=1e-12, atol=1e-12 * np.abs(mt).max())
        np.testing.assert_allclose(got_r, mr, rtol=1e-12, atol=1e-12 * np.abs(mr).max())
        got_k = frame3d._bending_stiffness(EI, phi, L)
        np.testing.assert_allclose(got_k, k, rtol=1e-12, atol=1e-12 * np.abs(k).max())

    def test_tube_section(self):
        s = frame3d.tube(1.2, 0.03)
        self.assertAlmostEqual(s["A"], np.pi * (1.2**2 - 1.14**2) / 4, places=14)
        self.assertAlmostEqual(s["Iy"], np.pi * (1.2**4 - 1.14**4) / 64, places=14)
        self.assertEqual(s["J"], 2 * s["Iy"])
        self.assertEqual(s["kappa"], 0.5)
        # Thin-wall limits: A -> pi D t, I -> pi D^3 t / 8 (to O(t / D) = 2.5 %).
        # With the mean diameter Dm = D - t: A = pi Dm t and
        # I = pi Dm t (Dm^2 + t^2) / 8, exact identities (1e-12).
        Dm, t = 1.17, 0.03
        self.assertAlmostEqual(s["A"] / (np.pi * Dm * t), 1.0, places=12)
        self.assertAlmostEqual(s["Iy"] / (np.pi * Dm * t * (Dm**2 + t**2) / 8), 1.0, places=12)


class CantileverTest(unittest.TestCase):
    def test_bending_frequencies_in_both_planes_along_any_direction(self):
        # Clamped-free, beta_k L = 1.8751, 4.6941, in each principal plane
        # (displacement along local z bends about y: I_y; along y: I_z). Bar
        # L / r > 440: shear deformation and rotary inertia, absent from the
        # closed form, lower mode 2 by ~(1 + E / kappa G) (beta_2 r)^2 / 2
        # ~ 2e-4 (measured: 3.3e-4 at most); 20 cubic elements add < 1e-6.
        # Tolerance 1e-3.
        L = 20.0
        for name, d in DIRECTIONS.items():
            for ref in ((None, (1.0, 0.0, 0.0)) if name == "skew" else (None,)):
                f, _, nodes = cantilever(d, 20, L, BAR, ref=ref)
                freqs, shapes = f.modes(8)
                kinds = classify(f, shapes, nodes, ref)
                for axis, I in (("z", BAR["Iy"]), ("y", BAR["Iz"])):
                    got = [fr for fr, k in zip(freqs, kinds) if k[axis] > 0.99][:2]
                    want = [bl**2 / (2 * np.pi * L * L) * np.sqrt(E * I / (RHO * BAR["A"]))
                            for bl in BETA_L]
                    self.assertEqual(len(got), 2, (name, ref, axis))
                    for g, w in zip(got, want):
                        self.assertAlmostEqual(g / w, 1.0, delta=1e-3, msg=(name, ref, axis))

    def test_axial_and_torsional_frequencies(self):
        # pi/2 sqrt(E / rho) / L and pi/2 sqrt(G J / (rho I_p)) / L. Linear
        # elements with consistent mass overestimate omega by (k h)^2 / 24
        # (k = pi / 2L, h = L / 40: 6e-5). Tolerance 3e-4.
        L = 10.0
        for name, d in DIRECTIONS.items():
            f, _, nodes = cantilever(d, 40, L, BAR)
            freqs, shapes = f.modes(40)
            kinds = classify(f, shapes, nodes)
            axial = first(freqs, kinds, "x")
            torsion = first(freqs, kinds, "torsion")
            self.assertAlmostEqual(axial / (np.sqrt(E / RHO) / (4 * L)), 1.0, delta=3e-4,
                                   msg=name)
            want = np.sqrt(G * BAR["J"] / (RHO * BAR["Ip"])) / (4 * L)
            self.assertAlmostEqual(torsion / want, 1.0, delta=3e-4, msg=name)

    def test_free_free_bar_rigid_modes_and_first_bending(self):
        # Unsupported: six rigid-body modes (0 Hz; the dense solver's K-based
        # form leaves them at rounding level, < 1e-3 Hz), then beta L = 4.7300
        # about the weaker axis (shear and rotary inertia: measured -9e-5;
        # tolerance 1e-3), with both solvers (sparse: shift sigma = -1).
        f = Frame3d()
        a, b = f.add_node(0, 0, 0), f.add_node(*(20.0 * SKEW))
        f.add_member(a, b, 60, E=E, G=G, rho=RHO, **BAR)
        want = 4.7300408**2 / (2 * np.pi * 400.0) * np.sqrt(E * BAR["Iz"] / (RHO * BAR["A"]))
        for kw in (dict(), dict(dense_limit=0, sigma=-1.0)):
            freqs, _ = f.modes(7, **kw)
            self.assertLess(max(freqs[:6]), 1e-3)
            self.assertAlmostEqual(freqs[6] / want, 1.0, delta=1e-3)

    def test_timoshenko_tip_deflection_is_exact(self):
        # P L^3 / 3EI + P L / (kappa G A) along local y (I_z) and z (I_y),
        # P L / EA along the member, T L / GJ in torsion: exact for end loads
        # with any mesh (the stiffness is the member's exact static one), so to
        # rounding (1e-9), on a stocky tube where shear is 14 % of the tip
        # deflection.
        s = frame3d.tube(1.2, 0.03)
        L, P = 4.0, 1e5
        for name, d in DIRECTIONS.items():
            for parts in (1, 3):
                f, tip, nodes = cantilever(d, parts, L, dict(s, Iz=1.5 * s["Iz"]))
                _, R = frame3d.local_axes(f.xyz[nodes[0]], f.xyz[nodes[-1]])
                bend = {1: s["Iz"] * 1.5, 2: s["Iy"]}
                for axis in (0, 1, 2):
                    loads = {(tip, i): P * R[axis, i] for i in range(3)}
                    u = f.static(loads)[6 * tip:6 * tip + 3] @ R[axis]
                    if axis == 0:
                        want = P * L / (E * s["A"])
                    else:
                        want = P * L**3 / (3 * E * bend[axis]) + P * L / (0.5 * G * s["A"])
                    self.assertAlmostEqual(u / want, 1.0, places=9, msg=(name, parts, axis))
                loads = {(tip, 3 + i): P * R[0, i] for i in range(3)}
                rot = f.static(loads)[6 * tip + 3:6 * tip + 6] @ R[0]
                self.assertAlmostEqual(rot / (P * L / (G * s["J"])), 1.0, places=9)
                if name == "x" and parts == 3:
                    shear = P * L / (0.5 * G * s["A"]) / want
                    self.assertGreater(shear, 0.1)


class SupportTest(unittest.TestCase):
    def test_base_rotational_spring(self):
        # frame2d's closed form: tip deflection P L^3 / 3EI + P L^2 / k_r, exact.
        kr = 3e7
        f = Frame3d()
        a, t = f.add_node(0, 0, 0), f.add_node(0, 0, 3.0)
        b = 0.3
        f.add_member(a, t, 2, E=E, G=G, shear=False, A=b * b, I=b**4 / 12, rho=RHO)
        f.fix(a, (UX, UY, UZ, RX, RZ))
        f.springs.append((a, RY, kr))
        u = f.static({(t, UX): 1e4})
        want = 1e4 * 27 / (3 * E * b**4 / 12) + 1e4 * 9 / kr
        self.assertAlmostEqual(u[6 * t + UX] / want, 1.0, places=9)

    def test_rigid_column_rocking_on_a_spring(self):
        # A near-rigid column (EI 1e5 k_r h, EA 1e5 k_z h, mass 1e-6 of the
        # head's) with a point mass m and rotary inertia J on top, rocking on a
        # base spring: f = sqrt(k_r / (m h^2 + J)) / 2 pi; and the head's
        # vertical bounce on a base translational spring, sqrt(k_z / m) / 2 pi.
        # The column's flexibility lowers them by k_r h / 6EI ~ 2e-6 and
        # k_z h / 2EA = 5e-6: tolerance 2e-5, with the dense and the sparse
        # solvers (a badly conditioned M: 1e-6 kg-scale nodes beside 2e4 kg).
        kr, kz, h, m, J = 4e8, 2e9, 5.0, 2e4, 3e3
        f = Frame3d()
        a, t = f.add_node(0, 0, 0), f.add_node(0, 0, h)
        I, A = kr * h / E * 1e5, kz * h / E * 1e5
        f.add_member(a, t, 2, E=E, G=G, shear=False, A=A, I=I, rho=m * 1e-6 / (A * h))
        f.fix(a, (UX, UY, RX, RZ))
        f.springs += [(a, RY, kr), (a, UZ, kz)]
        f.point_masses.append((t, m, J))
        f.fix(t, (UY, RX, RZ))
        want = np.array(sorted([np.sqrt(kr / (m * h * h + J)), np.sqrt(kz / m)])) / (2 * np.pi)
        for dense_limit in (600, 0):
            freqs, _ = f.modes(2, dense_limit=dense_limit)
            np.testing.assert_allclose(freqs, want, rtol=2e-5)

    def test_spring_between_nodes_in_series(self):
        # Two springs in series to ground through a coupling: u = P (1/k1 + 1/k2).
        f = Frame3d()
        a, b = f.add_node(0, 0, 0), f.add_node(1, 0, 0)
        f.fixed |= {(a, d) for d in range(1, 6)} | {(b, d) for d in range(1, 6)}
        f.springs.append((a, UX, 2e6))
        f.couplings.append((a, b, UX, 5e6))
        u = f.static({(b, UX): 1e3})
        self.assertAlmostEqual(u[6 * b] / (1e3 * (1 / 2e6 + 1 / 5e6)), 1.0, places=12)


def portal2d(h, L, parts, col, beam):
    f = frame2d.Frame()
    n0, n1 = f.add_node(0, 0), f.add_node(L, 0)
    t0, t1 = f.add_node(0, h), f.add_node(L, h)
    t2 = f.add_node(L, 2 * h)
    for base, top, s in ((n0, t0, col), (n1, t1, col), (t1, t2, col), (t0, t1, beam),
                         (t0, t2, beam)):
        f.add_member(base, top, parts, E=E, G=G, rho=RHO, **s)
    f.fixed |= {(n0, 0), (n0, 1), (n0, 2), (n1, 0), (n1, 1)}
    f.springs.append((n1, 2, 5e7))
    f.point_masses.append((t2, 3e3, 0.0))
    return f


def portal3d(h, L, parts, col, beam, mass_kind):
    """frame2d's portal with its x-y plane laid in the x-z plane of frame3d; the
    out-of-plane DOFs (uy, rx, rz) restrained. In-plane bending is about local
    y for both columns (ref X) and beams (ref Z): I_y = frame2d's I; I_z is set
    3 times larger to show it plays no part."""
    f = Frame3d()
    f.mass_kind = mass_kind
    n0, n1 = f.add_node(0, 0, 0), f.add_node(L, 0, 0)
    t0, t1 = f.add_node(0, 0, h), f.add_node(L, 0, h)
    t2 = f.add_node(L, 0, 2 * h)
    for base, top, s in ((n0, t0, col), (n1, t1, col), (t1, t2, col), (t0, t1, beam),
                         (t0, t2, beam)):
        f.add_member(base, top, parts, E=E, G=G, rho=RHO, A=s["A"], Iy=s["I"], Iz=3 * s["I"],
                     kappa=s.get("kappa", 5 / 6))
    for n in range(len(f.xyz)):
        f.fix(n, (UY, RX, RZ))
    f.fix(n0, (UX, UZ, RY))
    f.fix(n1, (UX, UZ))
    f.springs.append((n1, RY, 5e7))
    f.point_masses.append((t2, 3e3, 0.0))
    return f


class CrossCheckTest(unittest.TestCase):
    # A stocky two-storey frame with a diagonal, a base spring and a point mass
    # (phi up to ~0.3 per element), in frame2d and in frame3d's x-z plane.
    COL = dict(A=0.12, I=2.5e-3)
    BEAM = dict(A=0.08, I=1.2e-3, kappa=0.6)

    def test_portal_in_xz_plane_matches_frame2d_hermite(self):
        # Same formulation (Timoshenko stiffness, Hermite + rotary mass), two
        # codes: equal to rounding of the eigensolver (1e-9).
        f2 = portal2d(3.5, 6.0, 4, self.COL, self.BEAM)
        f3 = portal3d(3.5, 6.0, 4, self.COL, self.BEAM, "hermite")
        a, _ = f2.modes(6)
        b, _ = f3.modes(6)
        np.testing.assert_allclose(b, a, rtol=1e-9)

    def test_portal_in_xz_plane_matches_frame2d_timoshenko_mass(self):
        # frame3d's default Timoshenko mass against frame2d's Hermite mass.
        # Not quite the same continuum: frame2d's rotary inertia acts on the
        # slope v' (Hermite shapes), frame3d's on the section rotation psi =
        # v' - shear strain, a second-order difference in these stocky members
        # that mesh refinement does not remove (frame2d tends to 1e-4-7e-4
        # below frame3d's converged values; frame3d converges from above,
        # 3e-4 at 16 elements). Measured at 16 elements: < 1e-3 on the 6
        # lowest modes. Tolerance 2e-3.
        f2 = portal2d(3.5, 6.0, 16, self.COL, self.BEAM)
        f3 = portal3d(3.5, 6.0, 16, self.COL, self.BEAM, "timoshenko")
        a, _ = f2.modes(6)
        b, _ = f3.modes(6)
        np.testing.assert_allclose(b, a, rtol=2e-3)

    def test_rotated_frame_has_the_same_frequencies(self):
        # The unrestrained 3D portal rotated about an arbitrary axis (nodes and
        # reference vectors rotated alike): frequencies invariant to 1e-9.
        def build(Q):
            f = Frame3d()
            pts = [(0, 0, 0), (6, 0, 0), (0, 0, 3.5), (6, 0, 3.5), (6, 2, 3.5)]
            n = [f.add_node(*(Q @ p)) for p in pts]
            s = frame3d.tube(0.5, 0.02)
            for a, b, ref in ((0, 2, (1, 0, 0)), (1, 3, (1, 0, 0)), (2, 3, (0, 0, 1)),
                              (3, 4, (0, 0, 1))):
                f.add_member(n[a], n[b], 3, E=E, G=G, rho=RHO, ref=Q @ np.array(ref, float), **s)
            f.fix(n[0])
            f.fix(n[1])
            return f.modes(8)[0]
        ang = 0.7
        axis = SKEW
        Kx = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        Q = np.eye(3) + np.sin(ang) * Kx + (1 - np.cos(ang)) * Kx @ Kx
        np.testing.assert_allclose(build(Q), build(np.eye(3)), rtol=1e-9)


class MassTest(unittest.TestCase):
    def test_added_mass_transverse_only(self):
        # A submerged tube (0.6 m x 15 mm, L 40 m, L / r = 193) with marine
        # growth (a line mass, all directions) and hydrodynamic added mass
        # (transverse only): transverse frequencies scale by
        # sqrt(m / (m + m_g + m_a)), m = rho A; the axial one by
        # sqrt(m / (m + m_g)) only. The section's rotary inertia (rho I) is
        # not scaled, which moves the bending ratio by about its share of the
        # kinetic energy, ~(beta r)^2 / 2 (measured: 4e-5 for the first pair of
        # modes, 2.8e-4 for the second; 1.1e-3 at L = 20 m): tolerance 1e-3.
        # The axial mode of a straight member is decoupled from bending: its
        # ratio holds to rounding (1e-8; measured 6e-13).
        s = frame3d.tube(0.6, 0.015)
        ma = frame3d.hydrodynamic_added_mass(0.65, Ca=1.0)
        mg = frame3d.marine_growth_mass(0.6, 0.025)
        m = RHO * s["A"]
        for name, d in DIRECTIONS.items():
            dry, _, nodes = cantilever(d, 24, 40.0, s)
            wet, _, _ = cantilever(d, 24, 40.0, s, added_mass=ma, line_mass=mg)
            fd, vd = dry.modes(30)
            fw, vw = wet.modes(30)
            kd, kw = classify(dry, vd, nodes), classify(wet, vw, nodes)
            # A tube bends alike in both planes: the first two pairs of
            # transverse modes (any mix of local y and z).
            bd = [fr for fr, k in zip(fd, kd) if k["y"] + k["z"] > 0.99][:4]
            bw = [fr for fr, k in zip(fw, kw) if k["y"] + k["z"] > 0.99][:4]
            self.assertEqual(len(bw), 4)
            for a, b in zip(bd, bw):
                self.assertAlmostEqual(b / a / np.sqrt(m / (m + mg + ma)), 1.0, delta=1e-3,
                                       msg=name)
            ad = first(fd, kd, "x")
            aw = first(fw, kw, "x")
            self.assertAlmostEqual(aw / ad / np.sqrt(m / (m + mg)), 1.0, places=8, msg=name)
            # Added mass alone leaves the axial frequency unchanged.
            wet2, _, _ = cantilever(d, 24, 40.0, s, added_mass=ma)
            f2, v2 = wet2.modes(30)
            a2 = first(f2, classify(wet2, v2, nodes), "x")
            self.assertAlmostEqual(a2 / ad, 1.0, places=8, msg=name)

    def test_mass_of_a_rigid_translation(self):
        # Sum of member and line masses; the added mass counts by the square of
        # the sine between the translation and the member. Exact (1e-10).
        f = Frame3d()
        a, b, c = f.add_node(0, 0, 0), f.add_node(*(5 * SKEW)), f.add_node(5 * SKEW[0], 0, 0)
        f.add_member(a, b, 4, E=E, G=G, A=0.01, I=1e-5, rho=RHO, line_mass=120.0,
                     added_mass=300.0)
        f.add_member(b, c, 3, E=E, G=G, A=0.02, I=1e-5, rho=RHO)
        f.point_masses.append((c, 700.0, 50.0))
        f.fix(a)
        L2 = float(np.linalg.norm(5 * SKEW - [5 * SKEW[0], 0, 0]))
        d2 = (np.array([5 * SKEW[0], 0, 0]) - 5 * SKEW) / L2
        for e in (np.eye(3)[0], np.eye(3)[1], np.eye(3)[2], SKEW, np.array([1.0, -1.0, 0.3])):
            e = e / np.linalg.norm(e)
            want = ((RHO * 0.01 + 120.0) * 5.0 + 300.0 * 5.0 * (1 - (e @ SKEW) ** 2)
                    + RHO * 0.02 * L2 + 700.0)
            self.assertAlmostEqual(f.rigid_translation_mass(e) / want, 1.0, places=10)
        self.assertAlmostEqual(d2 @ d2, 1.0)

    def test_sparse_and_dense_solvers_agree(self):
        # Shift-invert Lanczos against dense eigh on the same model (1e-7: the
        # shift-invert solves' rounding, measured 5e-9), and
        # mass-normalised shapes (phi' M phi = I).
        f, _, _ = cantilever(SKEW, 30, 10.0, BAR)
        a, va, M, free = f.solve(6)
        b, vb, _, _ = f.solve(6, dense_limit=0)
        np.testing.assert_allclose(b, a, rtol=1e-7)
        for v in (va, vb):
            g = v[free].T @ (M @ v[free])
            np.testing.assert_allclose(g, np.eye(6), atol=1e-9)


if __name__ == "__main__":
    unittest.main()
