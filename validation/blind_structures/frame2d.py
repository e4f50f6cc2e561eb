"""A plane frame in numpy, written apart from femup, to make blind truths.

The truths of the blind structure suites must come from another formulation
than the models femup diagnoses (a chain of springs and masses, femup's own
Euler-Bernoulli frame elements). This module is that other formulation:

- Timoshenko beam-column elements (shear deformation, exact static stiffness
  of a prismatic member) with axial stiffness, three DOFs per node (ux, uy, rz);
- consistent mass: axial, transverse (cubic) and rotary inertia, plus a
  non-structural line mass (slabs on beams) that moves in both directions;
- rotational springs at supports (a foundation's flexibility) and at member
  ends (semi-rigid joints), as springs between a node and a hinge node;
- a sparse generalised eigensolver (shift-invert Lanczos, scipy) for the lowest
  modes, and a dense one for small models.

Units: SI (m, kg, N). Nothing here reads or calls femup.
"""
import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as spl


class Frame:
    """Nodes (x, y), members meshed into elements, supports and springs."""

    def __init__(self):
        self.xy = []  # node coordinates
        # Elements: dicts n1, n2, E, G, A, I, kappa, rho, line_mass, tags and
        # optionally axial_area (the axial stiffness's area, default A).
        self.elements = []
        self.fixed = set()  # (node, dof) restrained
        self.springs = []  # (node, dof, stiffness) to ground
        self.couplings = []  # (node_a, node_b, dof, stiffness) between nodes
        self.point_masses = []  # (node, mass, rotary inertia)
        # Tied DOFs: ties[(b, dof)] = a: node b's dof is node a's (a hinge node
        # sharing a joint's translations, with a rotational spring between).
        self.ties = {}

    def add_node(self, x, y):
        self.xy.append((float(x), float(y)))
        return len(self.xy) - 1

    def add_member(self, a, b, parts, **props):
        """Meshes the straight member a -> b into `parts` elements; returns the
        element indices and the interior node indices (a, ..., b)."""
        (xa, ya), (xb, yb) = self.xy[a], self.xy[b]
        nodes = [a]
        for k in range(1, parts):
            t = k / parts
            nodes.append(self.add_node(xa + t * (xb - xa), ya + t * (yb - ya)))
        nodes.append(b)
        first = len(self.elements)
        for k in range(parts):
            e = dict(kappa=5.0 / 6.0, line_mass=0.0, tags=set())
            e.update(props)
            e["tags"] = set(props.get("tags", ()))
            e["n1"], e["n2"] = nodes[k], nodes[k + 1]
            self.elements.append(e)
        return list(range(first, len(self.elements))), nodes

    def semi_rigid_end(self, joint, stiffness):
        """A new node at `joint` sharing its translations, joined to it in
        rotation by a spring of `stiffness` (N m/rad): connect a member's end
        to the returned node for a semi-rigid joint."""
        x, y = self.xy[joint]
        b = self.add_node(x, y)
        self.ties[(b, 0)] = joint
        self.ties[(b, 1)] = joint
        self.couplings.append((joint, b, 2, stiffness))
        return b

    def num_dofs(self):
        return 3 * len(self.xy)

    def element_length(self, e):
        (x1, y1), (x2, y2) = self.xy[e["n1"]], self.xy[e["n2"]]
        return float(np.hypot(x2 - x1, y2 - y1))

    def _local(self, e):
        (x1, y1), (x2, y2) = self.xy[e["n1"]], self.xy[e["n2"]]
        length = float(np.hypot(x2 - x1, y2 - y1))
        c, s = (x2 - x1) / length, (y2 - y1) / length
        R = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
        T = np.zeros((6, 6))
        T[:3, :3] = R
        T[3:, 3:] = R
        return length, T

    @staticmethod
    def element_stiffness_local(E, G, A, I, kappa, length, axial_area=None):
        """Timoshenko beam-column stiffness, local (u1, v1, r1, u2, v2, r2).
        `axial_area` (default A) carries the axial stiffness only."""
        L = length
        phi = 12.0 * E * I / (kappa * G * A * L * L) if G > 0 else 0.0
        a = E * (A if axial_area is None else axial_area) / L
        b = E * I / ((1.0 + phi) * L**3)
        k = np.zeros((6, 6))
        k[0, 0] = k[3, 3] = a
        k[0, 3] = k[3, 0] = -a
        idx = [1, 2, 4, 5]
        kb = b * np.array(
            [
                [12, 6 * L, -12, 6 * L],
                [6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L],
                [-12, -6 * L, 12, -6 * L],
                [6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L],
            ]
        )
        k[np.ix_(idx, idx)] = kb
        return k

    @staticmethod
    def element_mass_local(rho, A, I, line_mass, length):
        """Consistent mass, local: axial, cubic transverse, rotary inertia."""
        L = length
        m = rho * A + line_mass
        M = np.zeros((6, 6))
        M[np.ix_([0, 3], [0, 3])] = m * L / 6.0 * np.array([[2, 1], [1, 2]])
        idx = [1, 2, 4, 5]
        mt = m * L / 420.0 * np.array(
            [
                [156, 22 * L, 54, -13 * L],
                [22 * L, 4 * L * L, 13 * L, -3 * L * L],
                [54, 13 * L, 156, -22 * L],
                [-13 * L, -3 * L * L, -22 * L, 4 * L * L],
            ]
        )
        mr = rho * I / (30.0 * L) * np.array(
            [
                [36, 3 * L, -36, 3 * L],
                [3 * L, 4 * L * L, -3 * L, -L * L],
                [-36, -3 * L, 36, -3 * L],
                [3 * L, -L * L, -3 * L, 4 * L * L],
            ]
        )
        M[np.ix_(idx, idx)] = mt + mr
        return M

    def assemble(self):
        """Global K, M (sparse CSC) over the free DOFs, and the free DOF list."""
        n = self.num_dofs()
        rows, cols, kv, mv = [], [], [], []
        for e in self.elements:
            L, T = self._local(e)
            kl = self.element_stiffness_local(e["E"], e["G"], e["A"], e["I"], e["kappa"], L,
                                              e.get("axial_area"))
            ml = self.element_mass_local(e["rho"], e["A"], e["I"], e["line_mass"], L)
            kg = T.T @ kl @ T
            mg = T.T @ ml @ T
            d = [3 * e["n1"] + i for i in range(3)] + [3 * e["n2"] + i for i in range(3)]
            for i in range(6):
                for j in range(6):
                    rows.append(d[i])
                    cols.append(d[j])
                    kv.append(kg[i, j])
                    mv.append(mg[i, j])
        for node, dof, k in self.springs:
            rows.append(3 * node + dof)
            cols.append(3 * node + dof)
            kv.append(k)
            mv.append(0.0)
        for a, b, dof, k in self.couplings:
            ia, ib = 3 * a + dof, 3 * b + dof
            for (r, c, v) in ((ia, ia, k), (ib, ib, k), (ia, ib, -k), (ib, ia, -k)):
                rows.append(r)
                cols.append(c)
                kv.append(v)
                mv.append(0.0)
        for node, mass, inertia in self.point_masses:
            for dof, v in ((0, mass), (1, mass), (2, inertia)):
                rows.append(3 * node + dof)
                cols.append(3 * node + dof)
                kv.append(0.0)
                mv.append(v)
        K = sp.coo_matrix((kv, (rows, cols)), shape=(n, n)).tocsc()
        M = sp.coo_matrix((mv, (rows, cols)), shape=(n, n)).tocsc()
        # Tied DOFs fold onto their masters: K <- T' K T.
        master = list(range(n))
        for (b, dof), a in self.ties.items():
            master[3 * b + dof] = 3 * a + dof
        if self.ties:
            T = sp.coo_matrix((np.ones(n), (np.arange(n), master)), shape=(n, n)).tocsc()
            K = (T.T @ K @ T).tocsc()
            M = (T.T @ M @ T).tocsc()
        free = [i for i in range(n)
                if (i // 3, i % 3) not in self.fixed and master[i] == i]
        K = K[free][:, free]
        M = M[free][:, free]
        self._master = master
        return K, M, free

    def solve(self, count):
        """The lowest `count` modes: frequencies (Hz), mass-normalised shapes over
        all DOFs (restrained ones 0), and the free DOFs' mass matrix and list."""
        K, M, free = self.assemble()
        nf = K.shape[0]
        if nf <= 400 or count >= nf - 1:
            w, V = sl.eigh(K.toarray(), M.toarray(), subset_by_index=[0, min(count, nf) - 1])
        else:
            w, V = spl.eigsh(K, k=count, M=M, sigma=0.0, which="LM")
            order = np.argsort(w)
            w, V = w[order], V[:, order]
        # eigh and eigsh (random start vector) return each shape with an arbitrary sign;
        # fix it (largest-magnitude entry positive) so that a seed makes the same case,
        # shape noise included, on every run.
        V = V * np.where(V[np.argmax(np.abs(V), axis=0), np.arange(V.shape[1])] < 0, -1.0, 1.0)
        full = np.zeros((self.num_dofs(), V.shape[1]))
        full[free, :] = V
        full = full[self._master, :]
        return np.sqrt(np.maximum(w, 0.0)) / (2 * np.pi), full, M, free

    def modes(self, count):
        """The lowest `count` modes: frequencies (Hz) and shapes over all DOFs."""
        freqs, full, _, _ = self.solve(count)
        return freqs, full

    def static(self, loads):
        """Displacements (all DOFs) under nodal loads {(node, dof): force}."""
        K, _, free = self.assemble()
        f = np.zeros(self.num_dofs())
        for (node, dof), v in loads.items():
            f[3 * node + dof] += v
        f = np.bincount(self._master, weights=f, minlength=len(f))
        u = np.zeros(self.num_dofs())
        u[free] = spl.spsolve(K, f[free])
        return u[self._master]

    def total_translational_mass(self):
        """Mass moving with a unit rigid translation in x (from M itself)."""
        K, M, free = self.assemble()
        r = np.array([1.0 if i % 3 == 0 else 0.0 for i in free])
        return float(r @ (M @ r))
