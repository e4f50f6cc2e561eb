"""A space frame in numpy, written apart from femup, to make blind 3D truths.

The 3D counterpart of frame2d.py: the "measured" modes of a jacket (or any
space frame) must come from another formulation than femup's space_frame
model, so that a diagnosis can be checked honestly. This module is that other
formulation:

- Nodes (x, y, z), six DOFs per node, ordered (ux, uy, uz, rx, ry, rz):
  translations (m) then rotations (rad) about the global axes.
- Timoshenko beam-column elements: axial E A / L, torsion G J / L (St Venant,
  no warping), bending in both principal planes with shear deformation,
  phi = 12 E I / (kappa G A L^2) per plane. The stiffness is the exact static
  stiffness of a prismatic member under end loads (Przemieniecki), so a
  cantilever's tip deflection under a tip load, P L^3 / 3EI + P L / (kappa G A),
  is exact with any number of elements. shear=False on a member switches shear
  deformation off (Euler-Bernoulli bending, phi = 0; unlike frame2d, G = 0
  would also remove the torsional stiffness).
- Principal axes from a reference vector (OpenSees' "vecxz" convention): the
  local x axis runs from end 1 to end 2; the reference vector lies in the local
  x-z plane, so local z is its component normal to x and local y = z x x. The
  default reference vector is global Z, or global X when the member is
  vertical. I_y is the second moment about local y (bending in the local x-z
  plane: w and ry), I_z about local z (bending in the x-y plane: v and rz).
- Consistent mass, "Timoshenko" (default) or "hermite":
  * axial and torsional: linear interpolation, m L / 6 [2 1; 1 2] with m the
    mass per metre moving along the member, and rho I_p L / 6 [2 1; 1 2] (the
    polar moment of the section, I_p = I_y + I_z unless given);
  * transverse translational inertia and the rotary inertia of the section
    (rho I) in each bending plane, consistent with the same interpolation as
    the stiffness: with mass="timoshenko" the shape functions are the exact
    static deflections of a shear-deformable member (Przemieniecki's
    phi-dependent matrices, Friedman and Kosmatka 1993), which are
    variationally consistent with the stiffness above, so the element is a
    true Rayleigh-Ritz element and the frequencies converge from above; with
    mass="hermite" the cubic Hermite matrices of an Euler-Bernoulli beam
    (frame2d's mass, the two agree when phi = 0). Timoshenko is the default
    because the jackets' tubes are stocky elements (a 1.2 m leg in 2.5 m
    elements has phi ~ 1.7), where mixing a Timoshenko stiffness with Hermite
    mass converges more slowly and not from above.
  * a non-structural line mass `line_mass` (kg/m: equipment, paint, marine
    growth, entrained water) that moves with the element in all three
    translations (axial and transverse); and an added line mass
    `added_mass` (kg/m: the hydrodynamic added mass of a submerged member,
    Ca rho_w pi D^2 / 4) that acts only in the two directions transverse to the
    member: potential flow along a slender cylinder adds no inertia. Both use
    the translational shape functions only (no rotary or torsional inertia:
    their radius of gyration is that of a thin layer around the tube, and
    their share of rotary inertia is of order (D / L)^2 of their translational
    effect).
- Supports: fixed DOFs; springs to ground at any node DOF (soft foundations,
  piles); springs between two nodes' same DOF; point masses with rotary
  inertia (a scalar, or three values about global X, Y, Z).
- The lowest modes by a sparse shift-invert generalised eigensolver
  (scipy.sparse.linalg.eigsh with sigma, Lanczos), or a dense one (scipy.linalg.
  eigh) for small models: frequencies (Hz), mass-normalised shapes over all
  DOFs (restrained ones 0), the free DOFs' mass matrix and the free-DOF list.

`tube()` gives a circular tube's section. Units: SI (m, kg, N, Pa). Nothing
here reads or calls femup.
"""
import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as spl

UX, UY, UZ, RX, RY, RZ = range(6)
DOF_NAMES = ("ux", "uy", "uz", "rx", "ry", "rz")

# Shear coefficient of a thin-walled circular tube. The elementary value from
# the shear flow of a thin ring is kappa = 1/2 (the shear area is half the wall
# area: only the two flanks near the neutral axis carry the shear); Cowper
# (1966, J. Appl. Mech. 33:335) gives 2 (1 + nu) / (4 + 3 nu) = 0.53 for
# nu = 0.3. 0.5 is the value used in most codes (and femup's CircularTube),
# and is used here.
KAPPA_THIN_TUBE = 0.5


def tube(D, t, kappa=KAPPA_THIN_TUBE):
    """Section of a circular tube of outer diameter D and wall t (m):
    A = pi (D^2 - d^2) / 4, I_y = I_z = pi (D^4 - d^4) / 64, torsion constant
    J = I_p = 2 I (exact for a circular tube: its sections do not warp), and
    the shear coefficient kappa (0.5 by default, see KAPPA_THIN_TUBE).
    A dict ready to pass to Frame3d.add_member."""
    if not (D > 0 and 0 < t <= D / 2):
        raise ValueError("tube: need D > 0 and 0 < t <= D / 2, got D=%g t=%g" % (D, t))
    d = D - 2 * t
    A = np.pi * (D * D - d * d) / 4.0
    I = np.pi * (D**4 - d**4) / 64.0
    return dict(A=A, Iy=I, Iz=I, J=2 * I, Ip=2 * I, kappa=kappa)


def hydrodynamic_added_mass(D, Ca=1.0, rho_w=1025.0):
    """Added mass per metre (kg/m) of a submerged cylinder of outer diameter D
    moving transverse to its axis: Ca rho_w pi D^2 / 4 (potential flow gives
    Ca = 1 for a circular cylinder; rho_w of sea water 1025 kg/m^3)."""
    return Ca * rho_w * np.pi * D * D / 4.0


def marine_growth_mass(D, thickness, rho_growth=1325.0):
    """Mass per metre (kg/m) of a marine growth layer of `thickness` on a tube of
    outer diameter D: rho_growth pi ((D + 2 th)^2 - D^2) / 4. It moves with the
    tube in all directions (a `line_mass`); the hydrodynamic added mass is then
    that of the grown diameter D + 2 th."""
    return rho_growth * np.pi * ((D + 2 * thickness) ** 2 - D * D) / 4.0


def _bending_stiffness(EI, phi, L):
    """Timoshenko bending stiffness in a plane, DOFs (v1, th1, v2, th2) with
    th = dv/dx in the absence of shear (the x-y plane convention)."""
    b = EI / ((1.0 + phi) * L**3)
    return b * np.array(
        [
            [12, 6 * L, -12, 6 * L],
            [6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L],
            [-12, -6 * L, 12, -6 * L],
            [6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L],
        ]
    )


def _bending_mass(m, rhoI, phi, L, kind):
    """Consistent transverse mass (line mass m, kg/m) and rotary inertia (rho I)
    in a plane, DOFs (v1, th1, v2, th2) as _bending_stiffness. kind "timoshenko":
    Przemieniecki's phi-dependent matrices (the exact static shapes of a
    shear-deformable member); "hermite": cubic Hermite (phi = 0 in both)."""
    if kind == "hermite":
        phi = 0.0
    p, p2 = phi, phi * phi
    c = m * L / (1.0 + p) ** 2
    m11 = 13 / 35 + 7 / 10 * p + p2 / 3
    m12 = (11 / 210 + 11 / 120 * p + p2 / 24) * L
    m13 = 9 / 70 + 3 / 10 * p + p2 / 6
    m14 = -(13 / 420 + 3 / 40 * p + p2 / 24) * L
    m22 = (1 / 105 + p / 60 + p2 / 120) * L * L
    m24 = -(1 / 140 + p / 60 + p2 / 120) * L * L
    mt = c * np.array(
        [
            [m11, m12, m13, m14],
            [m12, m22, -m14, m24],
            [m13, -m14, m11, -m12],
            [m14, m24, -m12, m22],
        ]
    )
    r = rhoI / (L * (1.0 + p) ** 2)
    r12 = (1 / 10 - p / 2) * L
    r22 = (2 / 15 + p / 6 + p2 / 3) * L * L
    r24 = (-1 / 30 - p / 6 + p2 / 6) * L * L
    mr = r * np.array(
        [
            [6 / 5, r12, -6 / 5, r12],
            [r12, r22, -r12, r24],
            [-6 / 5, -r12, 6 / 5, -r12],
            [r12, r24, -r12, r22],
        ]
    )
    return mt, mr


# Local DOF indices of the two bending planes. In the x-z plane a positive ry
# lowers w (ry = -dw/dx), hence the sign flips S = diag(1, -1, 1, -1).
_XY = [1, 5, 7, 11]  # v1, rz1, v2, rz2
_XZ = [2, 4, 8, 10]  # w1, ry1, w2, ry2
_S = np.diag([1.0, -1.0, 1.0, -1.0])


def _phis(E, G, A, Iy, Iz, kappa, kappa_z, L, shear):
    """(phi_y, phi_z): shear flexibility over bending flexibility of the x-y
    plane (E I_z, kappa A) and of the x-z plane (E I_y, kappa_z A)."""
    if not shear or G <= 0:
        return 0.0, 0.0
    kz = kappa if kappa_z is None else kappa_z
    return 12.0 * E * Iz / (kappa * G * A * L * L), 12.0 * E * Iy / (kz * G * A * L * L)


def element_stiffness_local(E, G, A, Iy, Iz, J, kappa, L, kappa_z=None, shear=True):
    """12 x 12 Timoshenko beam-column stiffness, local DOFs
    (u1 v1 w1 rx1 ry1 rz1 u2 v2 w2 rx2 ry2 rz2). Bending in x-y (v, rz) uses
    E I_z and the shear area kappa A; in x-z (w, ry) E I_y and kappa_z A
    (kappa_z defaults to kappa). shear=False (or G = 0): Euler-Bernoulli
    bending (phi = 0); G J / L still carries the torsion."""
    phi_y, phi_z = _phis(E, G, A, Iy, Iz, kappa, kappa_z, L, shear)
    k = np.zeros((12, 12))
    a = E * A / L
    k[np.ix_([0, 6], [0, 6])] = a * np.array([[1, -1], [-1, 1]])
    t = G * J / L
    k[np.ix_([3, 9], [3, 9])] = t * np.array([[1, -1], [-1, 1]])
    k[np.ix_(_XY, _XY)] = _bending_stiffness(E * Iz, phi_y, L)
    k[np.ix_(_XZ, _XZ)] = _S @ _bending_stiffness(E * Iy, phi_z, L) @ _S
    return k


def element_mass_local(E, G, A, Iy, Iz, Ip, kappa, rho, L, line_mass=0.0, added_mass=0.0,
                       kind="timoshenko", kappa_z=None, shear=True, rotary=True):
    """12 x 12 consistent mass, local DOFs as element_stiffness_local: axial
    (rho A + line_mass), torsional (rho I_p), transverse (rho A + line_mass +
    added_mass) and the section's rotary inertia (rho I) in both planes
    (rotary=False leaves the last out, as some codes do)."""
    phi_y, phi_z = _phis(E, G, A, Iy, Iz, kappa, kappa_z, L, shear)
    M = np.zeros((12, 12))
    lin = L / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
    M[np.ix_([0, 6], [0, 6])] = (rho * A + line_mass) * lin
    M[np.ix_([3, 9], [3, 9])] = rho * Ip * lin
    mt = rho * A + line_mass + added_mass
    ri = rho if rotary else 0.0
    t, r = _bending_mass(mt, ri * Iz, phi_y, L, kind)
    M[np.ix_(_XY, _XY)] = t + r
    t, r = _bending_mass(mt, ri * Iy, phi_z, L, kind)
    M[np.ix_(_XZ, _XZ)] = _S @ (t + r) @ _S
    return M


def local_axes(p1, p2, ref=None):
    """Rotation R (rows: local x, y, z in global components) of the member
    p1 -> p2. `ref` lies in the local x-z plane; default global Z, or global X
    for a vertical member (within 1e-6 rad)."""
    d = np.asarray(p2, float) - np.asarray(p1, float)
    L = float(np.linalg.norm(d))
    if not L > 0:
        raise ValueError("zero-length member")
    ex = d / L
    if ref is None:
        ref = (1.0, 0.0, 0.0) if abs(ex[2]) > 1 - 1e-12 else (0.0, 0.0, 1.0)
    ref = np.asarray(ref, float)
    ez = ref - (ref @ ex) * ex
    nz = np.linalg.norm(ez)
    if nz < 1e-6 * np.linalg.norm(ref):
        raise ValueError("reference vector parallel to the member")
    ez /= nz
    ey = np.cross(ez, ex)
    return L, np.vstack([ex, ey, ez])


class Frame3d:
    """Nodes (x, y, z), members meshed into elements, supports, springs, masses."""

    def __init__(self):
        self.xyz = []  # node coordinates
        # Elements: dicts n1, n2, E, G, A, Iy, Iz, J, Ip, kappa, rho, line_mass,
        # added_mass, ref (reference vector or None), tags.
        self.elements = []
        self.fixed = set()  # (node, dof) restrained
        self.springs = []  # (node, dof, stiffness) to ground
        self.couplings = []  # (node_a, node_b, dof, stiffness) between nodes
        self.point_masses = []  # (node, mass, rotary inertia: scalar or (Ixx, Iyy, Izz))
        self.mass_kind = "timoshenko"  # or "hermite", see the module docstring

    def add_node(self, x, y, z):
        self.xyz.append((float(x), float(y), float(z)))
        return len(self.xyz) - 1

    def add_member(self, a, b, parts, **props):
        """Meshes the straight member a -> b into `parts` elements; returns the
        element indices and the node indices along it (a, ..., b).
        props: E, G, A, Iy, Iz, J, rho (required; or I for Iy = Iz = I), Ip
        (default Iy + Iz), kappa (default 5/6), kappa_z (default kappa),
        line_mass, added_mass (kg/m, default 0), ref (reference vector), shear
        (default True; False: Euler-Bernoulli bending), rotary (default True;
        False: no rotary inertia of the section), tags."""
        pa, pb = np.array(self.xyz[a]), np.array(self.xyz[b])
        nodes = [a]
        for k in range(1, parts):
            nodes.append(self.add_node(*(pa + k / parts * (pb - pa))))
        nodes.append(b)
        first = len(self.elements)
        for k in range(parts):
            e = dict(kappa=5.0 / 6.0, kappa_z=None, shear=True, rotary=True, line_mass=0.0,
                     added_mass=0.0, ref=None, tags=set())
            e.update(props)
            if "I" in e:
                e.setdefault("Iy", e["I"])
                e.setdefault("Iz", e.pop("I"))
            e.setdefault("J", e["Iy"] + e["Iz"])
            e.setdefault("Ip", e["Iy"] + e["Iz"])
            e["tags"] = set(props.get("tags", ()))
            e["n1"], e["n2"] = nodes[k], nodes[k + 1]
            self.elements.append(e)
        return list(range(first, len(self.elements))), nodes

    def fix(self, node, dofs=range(6)):
        self.fixed |= {(node, d) for d in dofs}

    def num_dofs(self):
        return 6 * len(self.xyz)

    def element_length(self, e):
        return float(np.linalg.norm(np.subtract(self.xyz[e["n2"]], self.xyz[e["n1"]])))

    def element_matrices(self, e):
        """Global 12 x 12 K and M of element dict e: T' k T, T = diag(R, R, R, R)."""
        L, R = local_axes(self.xyz[e["n1"]], self.xyz[e["n2"]], e["ref"])
        kl = element_stiffness_local(e["E"], e["G"], e["A"], e["Iy"], e["Iz"], e["J"],
                                     e["kappa"], L, e["kappa_z"], e["shear"])
        ml = element_mass_local(e["E"], e["G"], e["A"], e["Iy"], e["Iz"], e["Ip"], e["kappa"],
                                e["rho"], L, e["line_mass"], e["added_mass"], self.mass_kind,
                                e["kappa_z"], e["shear"], e["rotary"])
        T = np.kron(np.eye(4), R)
        return T.T @ kl @ T, T.T @ ml @ T

    def assemble(self):
        """Global K, M (sparse CSC) over the free DOFs, and the free DOF list."""
        n = self.num_dofs()
        rows, cols, kv, mv = [], [], [], []
        for e in self.elements:
            kg, mg = self.element_matrices(e)
            d = np.r_[6 * e["n1"] + np.arange(6), 6 * e["n2"] + np.arange(6)]
            rows.append(np.repeat(d, 12))
            cols.append(np.tile(d, 12))
            kv.append(kg.ravel())
            mv.append(mg.ravel())
        for node, dof, k in self.springs:
            rows.append([6 * node + dof])
            cols.append([6 * node + dof])
            kv.append([k])
            mv.append([0.0])
        for a, b, dof, k in self.couplings:
            ia, ib = 6 * a + dof, 6 * b + dof
            rows.append([ia, ib, ia, ib])
            cols.append([ia, ib, ib, ia])
            kv.append([k, k, -k, -k])
            mv.append([0.0] * 4)
        for node, mass, inertia in self.point_masses:
            rot = np.broadcast_to(np.asarray(inertia, float), (3,))
            rows.append(6 * node + np.arange(6))
            cols.append(6 * node + np.arange(6))
            kv.append(np.zeros(6))
            mv.append(np.r_[mass, mass, mass, rot])
        cat = (lambda xs: np.concatenate([np.asarray(x, float) for x in xs])) if rows else \
            (lambda xs: np.zeros(0))
        r, c = cat(rows).astype(int), cat(cols).astype(int)
        K = sp.coo_matrix((cat(kv), (r, c)), shape=(n, n)).tocsc()
        M = sp.coo_matrix((cat(mv), (r, c)), shape=(n, n)).tocsc()
        # Exact symmetry (T' k T is symmetric only to rounding).
        K = ((K + K.T) * 0.5).tocsc()
        M = ((M + M.T) * 0.5).tocsc()
        free = [i for i in range(n) if (i // 6, i % 6) not in self.fixed]
        return K[free][:, free], M[free][:, free], free

    def solve(self, count, sigma=0.0, dense_limit=600):
        """The lowest `count` modes: frequencies (Hz), mass-normalised shapes over
        all DOFs (restrained ones 0), and the free DOFs' mass matrix and list.
        Dense (scipy.linalg.eigh on M v = K v / omega^2, K's Cholesky factor;
        the plain K v = omega^2 M v if K is not positive definite) up to
        `dense_limit` free DOFs, else sparse shift-invert Lanczos about sigma
        (rad^2/s^2; a small negative sigma, e.g. -1, handles a structure with
        rigid-body modes)."""
        K, M, free = self.assemble()
        nf = K.shape[0]
        if nf <= dense_limit or count >= nf - 1:
            count = min(count, nf)
            Kd, Md = K.toarray(), M.toarray()
            try:
                # The lowest modes as the largest of M v = (1 / omega^2) K v: the
                # Cholesky factor is K's, as in shift-invert, so that nearly
                # massless DOFs (an ill-conditioned M) do not spoil them.
                lam, V = sl.eigh(Md, Kd, subset_by_index=[nf - count, nf - 1])
                w, V = 1.0 / lam[::-1], V[:, ::-1]
                V = V / np.sqrt(np.einsum("ij,ij->j", V, Md @ V))
            except (np.linalg.LinAlgError, sl.LinAlgError):
                # K singular (rigid-body modes): the plain form.
                w, V = sl.eigh(Kd, Md, subset_by_index=[0, count - 1])
        else:
            w, V = spl.eigsh(K, k=count, M=M, sigma=sigma, which="LM")
            order = np.argsort(w)
            w, V = w[order], V[:, order]
            # eigsh's vectors are M-orthonormal already; renormalise against drift.
            V = V / np.sqrt(np.einsum("ij,ij->j", V, M @ V))
        # Fix each shape's arbitrary sign (largest-magnitude entry positive), so
        # that a seed makes the same case on every run.
        V = V * np.where(V[np.argmax(np.abs(V), axis=0), np.arange(V.shape[1])] < 0, -1.0, 1.0)
        full = np.zeros((self.num_dofs(), V.shape[1]))
        full[free, :] = V
        return np.sqrt(np.maximum(w, 0.0)) / (2 * np.pi), full, M, free

    def modes(self, count, **kw):
        """The lowest `count` modes: frequencies (Hz) and shapes over all DOFs."""
        freqs, full, _, _ = self.solve(count, **kw)
        return freqs, full

    def static(self, loads):
        """Displacements (all DOFs) under nodal loads {(node, dof): force or moment}."""
        K, _, free = self.assemble()
        f = np.zeros(self.num_dofs())
        for (node, dof), v in loads.items():
            f[6 * node + dof] += v
        u = np.zeros(self.num_dofs())
        u[free] = spl.spsolve(K, f[free])
        return u

    def rigid_translation_mass(self, direction=(1.0, 0.0, 0.0)):
        """Mass moving with a unit rigid translation along `direction` (from M
        itself, restrained DOFs included)."""
        d = np.asarray(direction, float)
        d = d / np.linalg.norm(d)
        fixed, self.fixed = self.fixed, set()
        try:
            _, M, free = self.assemble()
        finally:
            self.fixed = fixed
        r = np.array([d[i % 6] if i % 6 < 3 else 0.0 for i in free])
        return float(r @ (M @ r))
