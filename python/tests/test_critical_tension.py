"""The critical tension from Python is the CLI's, and SciPy's eigsh on the exported A0, A1 gives the same load."""
import numpy as np
import pytest
import scipy.io
import scipy.sparse.linalg

import sphstab
from conftest import cli_error, csv_rows


def test_tcrit_equals_the_cli(cli):
    kernels, hs, forms = ["cubic", "quintic", "wendland-c2"], [1.0, 1.3, 1.7], ["conservative", "plus"]
    cases = sphstab.critical_tension(n=24, kernels=kernels, h=hs, forms=forms)
    rc, out, err = cli("tcrit", "--n", 24, "--kernel", ",".join(kernels), "--h", ",".join(map(str, hs)),
                       "--form", ",".join(forms))
    assert rc == 0, err
    rows = csv_rows(out)
    assert len(rows) == len(cases) == len(kernels) * len(hs) * len(forms)
    for c, r in zip(cases, rows):
        assert (c.kernel, c.form, c.status) == (r["kernel"], r["form"], r["status"])
        assert c.h_over_dx == float(r["h_over_dx"])
        for mine, theirs in [(c.tcrit, r["tcrit"]), (c.tcrit_eig, r["tcrit_eig"]), (c.tcrit_bisect, r["tcrit_bisect"])]:
            # The CLI prints 12 significant digits: the same number to the last printed digit.
            assert abs(mine - float(theirs)) <= 5e-12 * abs(mine) or (np.isnan(mine) and theirs.lower() == "nan")
    columns = sphstab.table(cases)
    assert columns["tcrit"].shape == (len(cases),)


@pytest.mark.parametrize("kernel,h,form", [("cubic", 1.3, "conservative"), ("quintic", 1.1, "plus"),
                                          ("wendland-c4", 1.6, "conservative")])
def test_eigsh_on_the_exported_linearisation_agrees_with_the_critical_load(cli, tmp_path, kernel, h, form):
    n = 40
    rc, _, err = cli("jacobian", "elastic", "--dim", 1, "--n", n, "--kernel", kernel, "--h", h, "--form", form,
                     "--out", tmp_path)
    assert rc == 0, err
    a0 = scipy.io.mmread(str(tmp_path / "A0.mtx")).tocsc()
    a1 = scipy.io.mmread(str(tmp_path / "A1.mtx")).tocsc()
    # A(T) = A0 + T A1 with A0 positive definite loses definiteness at T = 1 / lambda_max of -A1 x = lambda A0 x
    # (an independent route: ARPACK on the generalised problem instead of the library's Cholesky / LAPACK).
    lam = scipy.sparse.linalg.eigsh(-a1, k=1, M=a0, which="LA", return_eigenvectors=False)[0]
    (case,) = sphstab.critical_tension(n=n, kernels=[kernel], h=[h], forms=[form])
    assert case.status == "successful"
    assert abs(1.0 / lam - case.tcrit) <= 1e-8 * case.tcrit


def test_bad_input_raises_the_cli_message(cli):
    for kwargs, args in [({"kernels": ["nope"]}, ["--kernel", "nope"]), ({"forms": ["nope"]}, ["--form", "nope"]),
                         ({"method": "nope"}, ["--method", "nope"])]:
        with pytest.raises(ValueError) as e:
            sphstab.critical_tension(n=10, **kwargs)
        rc, _, err = cli("tcrit", "--n", 10, *args)
        assert rc == 1
        assert str(e.value) == cli_error(err)


@pytest.mark.parametrize("dim,args", [(1, dict(n=20, kernel="quintic", h=1.4, form="plus")),
                                      (2, dict(n=5, kernel="cubic", h=1.3, form="conservative", lattice="hex",
                                               prestrain="uniaxial"))])
def test_linearisation_equals_the_jacobian_export_bit_for_bit(cli, tmp_path, dim, args):
    flags = ["--dim", dim] + [x for k, v in args.items() for x in (f"--{k}", v)]
    rc, _, err = cli("jacobian", "elastic", "--out", tmp_path, *flags)
    assert rc == 0, err
    mine = sphstab.elastic_linearisation(dim=dim, **args)
    for name, m in zip(("A0", "A1"), mine):
        ref = scipy.io.mmread(str(tmp_path / f"{name}.mtx")).tocsr()
        ref.sort_indices()
        assert np.array_equal(m.indptr, ref.indptr) and np.array_equal(m.indices, ref.indices), name
        assert np.array_equal(m.data, ref.data), name


def test_critical_strain_equals_the_cli_and_eigsh(cli, tmp_path):
    kernels, hs, forms = ["cubic", "quintic"], [1.2, 1.5], ["conservative", "plus"]
    cases = sphstab.critical_strain(lattice="hex", n=8, kernels=kernels, h=hs, forms=forms, route="assembled")
    rc, out, err = cli("tcrit", "--dim", 2, "--lattice", "hex", "--n", 8, "--kernel", ",".join(kernels), "--h",
                       ",".join(map(str, hs)), "--form", ",".join(forms), "--route", "assembled")
    assert rc == 0, err
    rows = csv_rows(out)
    assert len(rows) == len(cases) == 8
    for c, r in zip(cases, rows):
        assert (c.kernel, c.form, c.status, c.criterion) == (r["kernel"], r["form"], r["status"], r["criterion"])
        for mine, theirs in [(c.ecrit, r["ecrit"]), (c.ecrit_infinite, r["ecrit_infinite"])]:
            assert abs(mine - float(theirs)) <= 5e-12 * abs(mine) or (np.isnan(mine) and theirs.lower() == "nan")
    # The conservative form's A(e) is symmetric: ARPACK on the exported pencil gives the same e_crit.
    c = cases[0]
    a0, a1 = sphstab.elastic_linearisation(dim=2, n=8, kernel="cubic", h=1.2, lattice="hex")
    lam = scipy.sparse.linalg.eigsh(-a1.tocsc(), k=1, M=a0.tocsc(), which="LA", return_eigenvectors=False)[0]
    assert abs(1.0 / lam - c.ecrit) <= 1e-8 * abs(c.ecrit)
    with pytest.raises(ValueError):
        sphstab.critical_strain(route="nope")
    with pytest.raises(ValueError):
        sphstab.critical_strain(lattice="pentagon")


def test_sizes_are_checked_before_anything_is_allocated():
    with pytest.raises(ValueError, match="h/dx must be finite and > 0"):
        sphstab.critical_tension(n=10, h=[float("nan")])
    with pytest.raises(sphstab.MemoryLimitError, match="needs"):
        sphstab.critical_tension(n=10**8)
    default = sphstab.max_memory()
    try:
        sphstab.set_max_memory("1M")  # the CLI's --max-memory 1M
        assert sphstab.max_memory() == 1e6
        with pytest.raises(sphstab.MemoryLimitError):
            sphstab.critical_strain(n=40, route="assembled")
        with pytest.raises(ValueError):
            sphstab.set_max_memory("lots")
    finally:
        sphstab.set_max_memory(None)
    assert sphstab.max_memory() == default
    assert issubclass(sphstab.MemoryLimitError, RuntimeError)
