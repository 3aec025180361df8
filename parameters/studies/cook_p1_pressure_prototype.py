#!/usr/bin/env python3
"""Cook's membrane in linear plane-strain elasticity (numpy/scipy, no
TissueFEM): tip u_y of linear triangles on the N x N grid split four ways
(the diagonal patterns of cook_triangulations.py), for the formulations
issue 30 weighs for a locking-free linear tetrahedron:

  P1             plain displacement (append 03 to a name for nu = 0.3)
  nodal          the nodally averaged dilatation (Bonet and Burton 1998),
                 linearized: what 'Formulation = nodal dilatation' is
  db             one pressure per vertex (P1-P1) with Dohrmann and Bochev's
                 (2004) projection stabilization, -(1/mu) |p - Pi_0 p|^2:
                 dim + 1 unknowns per vertex instead of the nodal system's
                 dim + 2
  nodalpressure  the same with the pressure's mass lumped

mu = 80.194 and nu = 0.4999 as in cook_membrane.prm, the clamped edge x = 0,
a unit vertical load spread over the edge x = 48. A prototype to choose an
element by, not a test: doc/studies.md ("What the nodal dilatation costs")
gives what it printed.

Usage: cook_p1_pressure_prototype.py N ELEMENT...  (e.g. 64 P103 nodal db)
"""
import sys
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
def corner(xi, eta):
    p00, p10, p01, p11 = (0, 0), (48, 44), (0, 44), (48, 60)
    return [(1-xi)*(1-eta)*p00[k]+xi*(1-eta)*p10[k]+(1-xi)*eta*p01[k]+xi*eta*p11[k] for k in range(2)]
def mesh(pattern, n):
    nodes = {}; X = []
    def node(key, xi, eta):
        if key not in nodes: nodes[key] = len(X); X.append(corner(xi, eta))
        return nodes[key]
    T = []
    for j in range(n):
        for i in range(n):
            a = node((2*i,2*j), i/n, j/n); b = node((2*i+2,2*j),(i+1)/n,j/n)
            c = node((2*i+2,2*j+2),(i+1)/n,(j+1)/n); d = node((2*i,2*j+2),i/n,(j+1)/n)
            kind = pattern
            if pattern == 'alternating': kind = 'right' if (i+j)%2==0 else 'left'
            if kind=='right': T += [(a,b,c),(a,c,d)]
            elif kind=='left': T += [(a,b,d),(b,c,d)]
            else:
                m = node((2*i+1,2*j+1),(i+.5)/n,(j+.5)/n); T += [(a,b,m),(b,c,m),(c,d,m),(d,a,m)]
    return np.array(X), np.array(T)
def grads(X, T):
    P = X[T]  # (ne,3,2)
    D = np.stack([P[:,1]-P[:,0], P[:,2]-P[:,0]], axis=2)  # columns
    A = 0.5*np.linalg.det(D)
    Dinv = np.linalg.inv(D)  # rows: grad of lambda1, lambda2
    G = np.zeros((len(T),3,2)); G[:,1]=Dinv[:,0,:]; G[:,2]=Dinv[:,1,:]; G[:,0]=-G[:,1]-G[:,2]
    return A, G
def Bmat(G):  # (ne, 3 strain comps [xx,yy,xy_eng], 6)
    ne = len(G); B = np.zeros((ne,3,6))
    B[:,0,0::2]=G[:,:,0]; B[:,1,1::2]=G[:,:,1]; B[:,2,0::2]=G[:,:,1]; B[:,2,1::2]=G[:,:,0]
    return B
mu = 80.194
def solve(X, T, nu, elem, alpha=1.0):
    kappa = 2*mu*(1+nu)/(3*(1-2*nu)); lam = kappa - 2*mu/3
    n = len(X); A, G = grads(X, T); B = Bmat(G); ne = len(T)
    dofs = np.zeros((ne,6),int); dofs[:,0::2]=2*T; dofs[:,1::2]=2*T+1
    m = np.array([1,1,0.])
    Ddev = mu*np.array([[4/3,-2/3,0],[-2/3,4/3,0],[0,0,1]])  # mu(2 e:e - 2/3 tr^2) as 1/2 e D e
    Dfull = Ddev + kappa*np.outer(m,m)
    def assemble(D):
        Ke = np.einsum('e,eia,ij,ejb->eab', A, B, D, B)
        r = np.repeat(dofs,6,axis=1).ravel(); c = np.tile(dofs,(1,6)).ravel()
        return sp.csr_matrix((Ke.ravel(),(r,c)),shape=(2*n,2*n))
    div = np.einsum('i,eia->ea', m, B)  # (ne,6) div of each dof shape
    if elem == 'P1':
        K = assemble(Dfull); nx = 2*n
    elif elem == 'nodal':  # linearized F-bar with vertex-averaged dilatation
        K = assemble(Ddev)
        # theta_b = sum_g A_g div_g / V_b ; cell thetabar_e = mean_b theta_b
        Vb = np.bincount(T.ravel(), np.repeat(A,3), n)
        rows = np.repeat(T,6,axis=1).ravel(); cols = np.tile(dofs,(1,3)).ravel()
        vals = (np.repeat((A[:,None]*div)[:,None,:],3,axis=1) / Vb[T][:,:,None]).ravel()
        Z = sp.csr_matrix((vals,(rows,cols)),shape=(n,2*n))
        Pm = sp.csr_matrix((np.full(3*ne,1/3),(np.repeat(np.arange(ne),3),T.ravel())),shape=(ne,n))
        Bbar = Pm @ Z
        K = K + Bbar.T @ sp.diags(kappa*A) @ Bbar
        nx = 2*n
    elif elem == 'db':  # u-p P1-P1, Dohrmann-Bochev projection stabilization
        K = assemble(Ddev)
        # B_up: int q div u = sum_e A_e/3 div_e for each vertex of e
        rows = np.repeat(T,6,axis=1).ravel(); cols = np.tile(dofs,(1,3)).ravel()
        vals = (np.repeat((A[:,None]*div/3)[:,None,:],3,axis=1)).ravel()
        Bup = sp.csr_matrix((vals,(rows,cols)),shape=(n,2*n))
        Me = np.einsum('e,ab->eab', A/12, np.ones((3,3))+np.eye(3))
        M0 = np.einsum('e,ab->eab', A/9, np.ones((3,3)))
        Ce = Me/kappa + alpha*(Me - M0)/mu
        r = np.repeat(T,3,axis=1).ravel(); c = np.tile(T,(1,3)).ravel()
        C = sp.csr_matrix((Ce.ravel(),(r,c)),shape=(n,n))
        K = sp.bmat([[K, Bup.T],[Bup, -C]]).tocsr(); nx = 3*n
    elif elem == 'nodalpressure':  # nodal pressure with lumped C (Bonet-Burton ANP) + optional stabilization
        K = assemble(Ddev)
        rows = np.repeat(T,6,axis=1).ravel(); cols = np.tile(dofs,(1,3)).ravel()
        vals = (np.repeat((A[:,None]*div/3)[:,None,:],3,axis=1)).ravel()
        Bup = sp.csr_matrix((vals,(rows,cols)),shape=(n,2*n))
        Vb = np.bincount(T.ravel(), np.repeat(A,3), n)/3
        Me = np.einsum('e,ab->eab', A/12, np.ones((3,3))+np.eye(3))
        M0 = np.einsum('e,ab->eab', A/9, np.ones((3,3)))
        r = np.repeat(T,3,axis=1).ravel(); c = np.tile(T,(1,3)).ravel()
        S = sp.csr_matrix(((alpha*(Me - M0)/mu).ravel(),(r,c)),shape=(n,n))
        C = sp.diags(Vb/kappa) + S
        K = sp.bmat([[K, Bup.T],[Bup, -C]]).tocsr(); nx = 3*n
    # load: right edge x=48, total vertical force 1 (uniform per length)
    f = np.zeros(nx)
    right = np.where(np.abs(X[:,0]-48)<1e-9)[0]; right = right[np.argsort(X[right,1])]
    for a,b in zip(right[:-1], right[1:]):
        L = X[b,1]-X[a,1]; f[2*a+1]+=L/2/16; f[2*b+1]+=L/2/16
    fixed = np.where(np.abs(X[:,0])<1e-9)[0]
    fixed = np.concatenate([2*fixed,2*fixed+1])
    free = np.setdiff1d(np.arange(nx), fixed)
    u = np.zeros(nx)
    u[free] = spl.spsolve(K[free][:,free].tocsc(), f[free])
    tip = np.where((np.abs(X[:,0]-48)<1e-9)&(np.abs(X[:,1]-60)<1e-9))[0][0]
    return u[2*tip+1]
if __name__ == '__main__':
    N = int(sys.argv[1]); elems = sys.argv[2:]
    for pat in ['right','left','crossed','alternating']:
        X,T = mesh(pat,N)
        print(pat, ' '.join('%s=%.5f'%(e, solve(X,T,0.4999 if not e.endswith('03') else 0.3, e.replace('03',''))) for e in elems), flush=True)
