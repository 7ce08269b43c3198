"""Block LOBPCG for the largest eigenvalues of L x = lambda K x (K SPD), with an SPD preconditioner T, and helpers.
Counts products with K and L (one product = one vector) and preconditioner applications."""
import time, numpy as np, scipy.linalg as sl

class Counted:
    def __init__(self, M, name):
        self.M = M; self.name = name; self.count = 0; self.time = 0.0
    def __call__(self, X):
        t = time.perf_counter()
        Y = self.M @ X if not callable(self.M) else self.M(X)
        self.time += time.perf_counter() - t
        self.count += 1 if X.ndim == 1 else X.shape[1]
        return Y

def _korth(S, KS, LS):
    """K-orthonormalise the columns of S (given KS, LS), dropping near-dependent directions."""
    G = S.T @ KS; G = 0.5 * (G + G.T)
    d = np.sqrt(np.abs(np.diag(G))); d[d == 0] = 1
    Gs = G / np.outer(d, d)
    w, V = np.linalg.eigh(Gs)
    keep = w > 1e-12 * w.max()
    C = (V[:, keep] / np.sqrt(w[keep])) / d[:, None]
    return S @ C, KS @ C, LS @ C

def zone_boundary_start(n, b):
    """Start block: (-1)^i / (-1)^j times sine envelopes, x- and y-directed, both polarisations."""
    i = np.arange(n); s = lambda m: np.sin(np.pi * m * (i + 1) / (n + 1))
    alt = (-1.0) ** i
    cols = []
    for (a, c) in [(1, 1), (1, 2), (2, 1), (2, 2), (1, 3), (3, 1), (3, 2), (2, 3)]:
        U = np.zeros((n, n, 2)); U[:, :, 0] = np.outer(s(c), alt * s(a)); cols.append(U.ravel())   # x-pol, k = (pi, 0)
        U = np.zeros((n, n, 2)); U[:, :, 1] = np.outer(alt * s(a), s(c)); cols.append(U.ravel())   # y-pol, k = (0, pi)
    X = np.array(cols[:b]).T
    return X

def _kproject(Y, KY, LY, Z, KZ, LZ):
    """Y <- Y - Z (Z^T K Y) for K-orthonormal Z (twice, for stability)."""
    for _ in range(2):
        C = KZ.T @ Y
        Y, KY, LY = Y - Z @ C, KY - KZ @ C, LY - LZ @ C
    return Y, KY, LY

def lobpcg(K, L, T, X0, maxit=5000, tol=1e-7, ref=None, nconv=1, verbose=False, log_every=0):
    """Largest eigenvalues of (L, K), block LOBPCG in the orthogonal-basis form of Hetmaniuk & Lehoucq (2006):
    W = T R is K-orthogonalised against X and P, P = the W/P part of the new Ritz vectors. Stop when the first
    nconv Ritz pairs have ||L x - theta K x|| / (theta ||K x||) < tol. K, L, T: callables on blocks (Counted)."""
    t0 = time.perf_counter()
    X = X0.copy(); b = X.shape[1]
    KX, LX = K(X), L(X)
    X, KX, LX = _korth(X, KX, LX)
    H = X.T @ LX; w, V = np.linalg.eigh(0.5 * (H + H.T)); V = V[:, ::-1]; w = w[::-1]
    X, KX, LX = X @ V, KX @ V, LX @ V
    P = KP = LP = None
    hist = []
    for it in range(1, maxit + 1):
        theta = w[:X.shape[1]]
        R = LX - KX * theta
        rn = np.linalg.norm(R, axis=0) / (np.abs(theta) * np.linalg.norm(KX, axis=0))
        hist.append((it, theta[0], rn[0]))
        if verbose and log_every and it % log_every == 0:
            err = abs(1 / theta[0] - ref) / ref if ref else float('nan')
            print(f'    it {it} theta {theta[0]:.12g} res {rn[0]:.2e} err {err:.2e}', flush=True)
        if np.all(rn[:nconv] < tol):
            break
        W = T(R)
        KW, LW = K(W), L(W)
        W, KW, LW = _kproject(W, KW, LW, X, KX, LX)
        if P is not None:
            W, KW, LW = _kproject(W, KW, LW, P, KP, LP)
        W, KW, LW = _korth(W, KW, LW)
        if P is None:
            Q, KQ, LQ = np.hstack([X, W]), np.hstack([KX, KW]), np.hstack([LX, LW])
        else:
            Q, KQ, LQ = np.hstack([X, W, P]), np.hstack([KX, KW, KP]), np.hstack([LX, LW, LP])
        G = Q.T @ KQ; H = Q.T @ LQ
        w, V = sl.eigh(0.5 * (H + H.T), 0.5 * (G + G.T)); V = V[:, ::-1]; w = w[::-1]
        Vx = V[:, :b]
        nb = X.shape[1]
        Vp = Vx[nb:, :]
        P, KP, LP = Q[:, nb:] @ Vp, KQ[:, nb:] @ Vp, LQ[:, nb:] @ Vp
        X, KX, LX = Q @ Vx, KQ @ Vx, LQ @ Vx
        P, KP, LP = _kproject(P, KP, LP, X, KX, LX)
        P, KP, LP = _korth(P, KP, LP)
        if P.shape[1] == 0:
            P = KP = LP = None
        if it % 100 == 0:   # refresh products (drift)
            KX, LX = K(X), L(X)
            X, KX, LX = _korth(X, KX, LX)
            H = X.T @ LX; w2, V2 = np.linalg.eigh(0.5 * (H + H.T)); V2 = V2[:, ::-1]
            X, KX, LX = X @ V2, KX @ V2, LX @ V2; w = np.concatenate([w2[::-1], w[b:]])
            P = KP = LP = None
    lam = w[0]
    return dict(lam=lam, e=1 / lam, it=it, res=rn[0], time=time.perf_counter() - t0, X=X, hist=hist, theta=w[:b])
