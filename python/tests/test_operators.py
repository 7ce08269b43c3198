"""Operators from Python equal the CLI's Matrix Market export bit for bit, and share the library's storage."""
import numpy as np
import pytest
import scipy.io

import sphstab
from conftest import cli_error, csv_rows


def exported(cli, tmp_path, *args):
    rc, out, err = cli("operators", "--out", tmp_path, *args)
    assert rc == 0, err
    return tmp_path


@pytest.mark.parametrize("dim,lattice,correction", [(1, "line", "ncsph"), (2, "square", "shepard"),
                                                    (2, "hex", "local-polish"), (3, "cubic", "none")])
def test_operators_equal_the_mtx_export_bit_for_bit(cli, tmp_path, dim, lattice, correction):
    n, h, kernel = (7, 1.3, "quintic") if dim < 3 else (3, 1.2, "cubic")
    d = exported(cli, tmp_path, "--dim", dim, "--lattice", lattice, "--n", n, "--h", h, "--kernel", kernel,
                 "--correction", correction, "--hessian")
    rows = csv_rows((d / "particles.csv").read_text())
    particles = sphstab.lattice(lattice, n, support_radius=sphstab.Kernel(kernel, dim).support_radius(h))
    axes = "xyz"[:dim]
    x_cli = np.array([[float(r[a]) for a in axes] for r in rows])
    assert np.array_equal(particles.x, x_cli)  # %.17g round-trips exactly
    ops = sphstab.operators(particles, kernel, h, hessian=True, correction=correction)
    names = ["W"] + [f"G_{a}" for a in axes] + [f"H_{a}{b}" for i, a in enumerate(axes) for b in axes[i:]]
    if correction != "none":
        names += [f"G_{correction}_{a}" for a in axes]
    assert sorted(ops) == sorted(names)
    for name in names:
        ref = scipy.io.mmread(str(d / f"{name}.mtx")).tocsr()
        mine = ops[name]
        assert mine.shape == ref.shape
        # Same stored pattern (explicit zeros included) and the same bits in every entry.
        ref.sort_indices()
        assert np.array_equal(mine.indptr, ref.indptr), name
        assert np.array_equal(mine.indices, ref.indices), name
        assert np.array_equal(mine.data, ref.data), name


def test_csr_matrices_view_the_library_storage_without_a_copy():
    ops = sphstab.operators(sphstab.lattice("square", 5, support_radius=2.6), "cubic", 1.3)
    g = ops["G_x"]
    for a in (g.data, g.indices, g.indptr):
        assert not a.flags.owndata  # a view: the capsule of the C++ matrix owns the memory
    assert g.indices.dtype == np.int32 and g.indptr.dtype == np.int32
    # Two routes to the same entries: G_x applied to the field x against the kernel sum written out here,
    # sum_j V_j W'(r_ij) (x_i - x_j) / r_ij x_j, and G_x applied to a constant is 0 on a complete neighbourhood.
    p = sphstab.lattice("square", 5, support_radius=2.6)
    k = sphstab.Kernel("cubic", 2)
    nl = sphstab.neighbours(p, k.support_radius(1.3))
    x = p.x
    direct = np.zeros(len(p))
    for i in range(len(p)):
        for j in nl.indices[nl.offsets[i]:nl.offsets[i + 1]]:
            if j != i:
                d = x[i] - x[j]
                r = np.hypot(*d)
                direct[i] += p.volume[j] * k.d1(np.array([r]), 1.3)[0] * d[0] / r * x[j, 0]
    assert np.allclose(g @ x[:, 0], direct, rtol=1e-13, atol=1e-13)
    free = ~p.fixed
    assert np.max(np.abs((g @ np.ones(len(p)))[free])) < 1e-13


def test_bad_input_raises_the_cli_message(cli, tmp_path):
    p = sphstab.lattice("line", 6, support_radius=2.6)
    for py_call, cli_args in [
        (lambda: sphstab.operators(p, "nonsense", 1.3), ["--kernel", "nonsense", "--correction", "none"]),
        (lambda: sphstab.operators(p, "cubic", 1.3, correction="nope"), ["--kernel", "cubic", "--correction", "nope"]),
        (lambda: sphstab.operators(p, "cubic", 1.3, counting="nope"), ["--kernel", "cubic", "--counting", "nope"]),
    ]:
        with pytest.raises(ValueError) as e:
            py_call()
        rc, _, err = cli("operators", "--dim", 1, "--lattice", "line", "--n", 6, "--h", 1.3, "--out", tmp_path,
                         *cli_args)
        assert rc == 1
        assert str(e.value) == cli_error(err)
    with pytest.raises(ValueError) as e:
        sphstab.lattice("line", 0)
    rc, _, err = cli("operators", "--dim", 1, "--lattice", "line", "--n", 0, "--h", 1.3, "--out", tmp_path)
    assert str(e.value) == cli_error(err)
    with pytest.raises(ValueError, match="unknown lattice|lattice"):
        sphstab.lattice("pentagonal", 4)
    with pytest.raises(ValueError):
        sphstab.ParticleSet2D(np.zeros((3, 3)), np.ones(3))  # three columns for a 2D set
    with pytest.raises(ValueError):
        sphstab.ParticleSet1D(np.zeros((3, 1)), -np.ones(3))  # negative volumes


def test_kernels_are_normalised_and_their_derivative_is_the_slope():
    for name in sphstab.kernel_names():
        k = sphstab.Kernel(name, 1)
        h = 0.7
        r = np.linspace(-k.support_radius(h), k.support_radius(h), 20001)
        w = k.value(np.abs(r), h)
        assert abs(np.trapz(w, r) - 1.0) < 1e-6, name  # 1D normalisation
        rr = np.linspace(0.1, 0.9 * k.support_radius(h), 7)
        eps = 1e-6
        slope = (k.value(rr + eps, h) - k.value(rr - eps, h)) / (2 * eps)
        assert np.allclose(k.d1(rr, h), slope, rtol=1e-5, atol=1e-8), name
    with pytest.raises(ValueError):
        sphstab.Kernel("cubic", 4)
