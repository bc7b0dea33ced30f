#!/usr/bin/env python3
"""pbrt-v4's rough `coateddiffuse` against kasha's closed form (docs/materials.md#coated-surfaces).

A Lambert base (rho 0.5) under a rough dielectric coat (eta 1.5, roughness 0.3 -> alpha = sqrt(0.3),
thickness 0), light and viewer at 45 degrees on opposite sides of the normal. Prints:
- kasha's closed form t(wi) t(wo) / (pi eta^2) * rho / (1 - Rbar rho), its tables computed here
  as host/material/coat.cpp computes them (visible-normal samples of the GGX interface);
- pbrt-v4's LayeredBxDF::f walk written out for this case (src/pbrt/bxdfs.h): entrance
  transmission from wo, a presampled transmission from wi for next-event estimation at the
  base, the base's cosine sample with "NEE along the BSDF sample" through the exit interface,
  internal reflection at the top, both NEE strategies weighed by the power heuristic — with the
  second strategy's weight taking exitInterface.PDF(-w, wi), as pbrt-v4 does;
- the same walk with that weight taking the density the first strategy has of the same
  direction (sampling -w from wi), so that the two weights sum to one.
The first and the last agree (0.0649); pbrt-v4's weighting gives 0.0719, 11 % more.
Run: /usr/bin/python3 scripts/check_pbrt_rough_coat.py (needs python3-numpy; about a minute).
"""
import numpy as np

rng=np.random.default_rng(1)
eta=1.5; alpha=np.sqrt(0.3); rho=0.5
def fresnel(c, eta):
    # c = cos on the incident side (>0), eta = n_t/n_i
    s2=(1-c*c)/(eta*eta)
    tir = s2>=1
    ct=np.sqrt(np.maximum(0,1-s2))
    rs=(c-eta*ct)/(c+eta*ct); rp=(eta*c-ct)/(eta*c+ct)
    F=0.5*(rs*rs+rp*rp)
    return np.where(tir,1.0,F)
def lam(wz):
    c2=wz*wz; t2=np.maximum(0,1-c2)/np.maximum(c2,1e-300)
    return (np.sqrt(1+alpha*alpha*t2)-1)/2
def sample_vis(w, u0, u1):
    # w: (n,3) with z>0
    wh=np.stack([alpha*w[:,0],alpha*w[:,1],w[:,2]],1); wh/=np.linalg.norm(wh,axis=1)[:,None]
    z=np.array([0,0,1.0])
    t1=np.cross(np.broadcast_to(z,wh.shape),wh); n1=np.linalg.norm(t1,axis=1)
    t1=np.where(n1[:,None]>1e-9, t1/np.maximum(n1,1e-300)[:,None], np.array([1.0,0,0]))
    t2=np.cross(wh,t1)
    r=np.sqrt(u0); phi=2*np.pi*u1; px=r*np.cos(phi); py=r*np.sin(phi)
    h=np.sqrt(np.maximum(0,1-px*px)); s=(1+wh[:,2])/2
    py=(1-s)*h+s*py; pz=np.sqrt(np.maximum(0,1-px*px-py*py))
    nh=px[:,None]*t1+py[:,None]*t2+pz[:,None]*wh
    m=np.stack([alpha*nh[:,0],alpha*nh[:,1],np.maximum(1e-9,nh[:,2])],1)
    return m/np.linalg.norm(m,axis=1)[:,None]
def albedos(mu, e, n=400000):
    wo=np.tile([np.sqrt(1-mu*mu),0,mu],(n,1))
    m=sample_vis(wo, rng.random(n), rng.random(n))
    c=np.sum(wo*m,1); F=fresnel(c,e)
    g1=1/(1+lam(wo[:,2]))
    wr=-wo+2*c[:,None]*m
    r=np.where(wr[:,2]>0, F/(1+lam(wo[:,2])+lam(wr[:,2]))/g1, 0).mean()
    s2=(1-c*c)/(e*e); ok=s2<1
    ct=np.sqrt(np.maximum(0,1-s2))
    wt=-wo/e+((c/e-ct)[:,None])*m; wt/=np.linalg.norm(wt,axis=1)[:,None]
    t=np.where(ok&(wt[:,2]<0),(1-F)/(1+lam(wo[:,2])+lam(wt[:,2]))/g1,0).mean()
    return r,t
mus=np.linspace(0.001,1,64)
tab=[albedos(m,eta) for m in mus]; tin=[albedos(m,1/eta) for m in mus]
T=np.array([t for r,t in tab]); Rin=np.array([r for r,t in tin])
# cosine mean
x=np.linspace(0,1,2001); w=2*x
Rbar=np.trapz(np.interp(x,mus,Rin)*w,x)
print("Rbar",Rbar)
for th in [20,45,70]:
    mu=np.cos(np.radians(th)); t=np.interp(mu,mus,T)
    print("theta",th,"t",t)
mi=np.cos(np.radians(45)); mo=np.cos(np.radians(45))
closed=np.interp(mi,mus,T)*np.interp(mo,mus,T)/(np.pi*eta*eta)*rho/(1-Rbar*rho)
print("closed form diffuse f at 45/45:",closed)

# ---- pbrt-v4's LayeredBxDF::f walk for this case (thickness 0, albedo 0), scalar, vectorised over samples
def D(m):  # GGX isotropic, m in local frame (z up)
    c2=m[:,2]**2; t2=np.maximum(0,1-c2)/np.maximum(c2,1e-300)
    return 1/(np.pi*alpha*alpha*c2*c2*(1+t2/(alpha*alpha))**2)
def G1(w): return 1/(1+lam(w[:,2]))
def G(a,b): return 1/(1+lam(a[:,2])+lam(b[:,2]))
def vis_pdf(w, m):  # pbrt's mf.PDF(w, m) = G1(w)/|cos w| D(m) |w.m|
    return G1(w)/np.abs(w[:,2])*D(m)*np.abs(np.sum(w*m,1))
def sample_vis_any(w,u0,u1):
    flip = w[:,2]<0
    ww=np.where(flip[:,None], -w, w)
    m=sample_vis(ww,u0,u1)
    return m  # pbrt: wm on the side of +z always (wh flipped to z>0)
def fresnel_any(c, eta):  # pbrt FrDielectric(cos_i, eta): cos_i<0 -> inside
    inside = c<0
    e=np.where(inside,1/eta,eta); cc=np.abs(c)
    return fresnel(cc,e)
def refract(wo, m, eta):
    # pbrt Refract(wo, n, eta, &etap, &wi): n flipped to wo side
    c=np.sum(wo*m,1); e=np.where(c<0,1/eta,eta); n=np.where(c[:,None]<0,-m,m); c=np.abs(c)
    s2=(1-c*c)/(e*e); ok=s2<1; ct=np.sqrt(np.maximum(0,1-s2))
    wi=-wo/e[:,None]+(c/e-ct)[:,None]*n
    return wi, e, ok
def sample_transmission(wo, radiance, n):
    m=sample_vis_any(wo, rng.random(n), rng.random(n))
    wi, etap, ok = refract(wo, m, eta)
    ok = ok & (wi[:,2]*wo[:,2] < 0)
    # weight f cos/pdf = (1-F) G/G1 (/etap^2 in radiance mode)
    F=fresnel_any(np.sum(wo*m,1), eta)
    wgt=(1-F)*G(wo,wi)/G1(wo)
    if radiance: wgt=wgt/etap**2
    # pdf of wi
    denom=(np.sum(wi*m,1)+np.sum(wo*m,1)/etap)**2
    dwm_dwi=np.abs(np.sum(wi*m,1))/denom
    pdf=vis_pdf(wo,m)*dwm_dwi*(1-F)/np.maximum((1-F),1e-300)  # pt/(pr+pt)=1
    return wi, np.where(ok,wgt,0), pdf, ok
def bt_f_pdf(wo, wi, radiance):
    # rough dielectric transmission f(wo, wi) and PDF(wo, wi, Transmission only)
    cos_o=wo[:,2]; cos_i=wi[:,2]
    etap=np.where(cos_o>0, eta, 1/eta)
    wm=wi*etap[:,None]+wo; wm/=np.linalg.norm(wm,axis=1)[:,None]
    wm=np.where(wm[:,2:3]<0,-wm,wm)
    ok=~((np.sum(wm*wo,1)*cos_o<0)|(np.sum(wm*wi,1)*cos_i<0)) & (cos_o*cos_i<0)
    F=fresnel_any(np.sum(wo*wm,1),eta); T=1-F
    denom=(np.sum(wi*wm,1)+np.sum(wo*wm,1)/etap)**2
    ft=T*D(wm)*G(wo,wi)*np.abs(np.sum(wi*wm,1)*np.sum(wo*wm,1)/(cos_i*cos_o*denom))
    if radiance: ft=ft/etap**2
    dwm_dwi=np.abs(np.sum(wi*wm,1))/denom
    pdf=vis_pdf(wo,wm)*dwm_dwi
    return np.where(ok,ft,0), np.where(ok,pdf,0)
def sample_reflection(wo, n):
    m=sample_vis_any(wo, rng.random(n), rng.random(n))
    c=np.sum(wo*m,1)
    wi=-wo+2*c[:,None]*m
    ok=wi[:,2]*wo[:,2]>0
    F=fresnel_any(c,eta)
    wgt=F*G(wo,wi)/G1(wo)
    return wi, np.where(ok,wgt,0), ok
def cosine_dir(n, up):  # up=+1 or -1
    u0=rng.random(n); u1=rng.random(n); r=np.sqrt(u0); phi=2*np.pi*u1
    return np.stack([r*np.cos(phi), r*np.sin(phi), up*np.sqrt(np.maximum(0,1-u0))],1)
def power(a,b): return a*a/np.maximum(a*a+b*b,1e-300)
def pbrt_f(th_o, th_i, n=2000000, depth_max=10, consistent_mis=False):
    # consistent_mis: the second strategy's weight takes the density the first has of the same
    # direction (sampling -wn from wi through the interface), so that the weights sum to one.
    wo=np.tile([np.sin(np.radians(th_o)),0,np.cos(np.radians(th_o))],(n,1))
    wi=np.tile([-np.sin(np.radians(th_i)),0,np.cos(np.radians(th_i))],(n,1))
    f=np.zeros(n)
    wos_w, wos_wt, _, ok1 = sample_transmission(wo, True, n)
    wis_w, wis_wt, wis_pdf, ok2 = sample_transmission(wi, False, n)
    alive=ok1&ok2&(wos_wt>0)&(wis_wt>0)
    beta=np.where(alive, wos_wt, 0); w=wos_w  # w points down (z<0)
    for depth in range(depth_max):
        # at the base (z=0): diffuse, two-sided handled as reflecting up
        # NEE along wis: diffuse f = rho/pi; its pdf for -w -> -wis: cos(-wis)/pi
        diff_pdf=np.abs(wis_w[:,2])/np.pi
        wt=power(wis_pdf, diff_pdf)
        f+=beta*(rho/np.pi)*np.abs(wis_w[:,2])*wt*wis_wt/np.maximum(np.abs(wis_w[:,2]),1e-300)
        # sample diffuse
        wn=cosine_dir(n, +1.0)
        beta=beta*rho
        # NEE along the BSDF sample: exit f(-wn -> wi)? pbrt: exitInterface.f(-w, wi) with w = new dir (up)
        fexit, pexit = bt_f_pdf(-wn, wi, True)
        if consistent_mis:
            _, pexit = bt_f_pdf(wi, -wn, False)
        bs_pdf=np.abs(wn[:,2])/np.pi
        wt=power(bs_pdf, pexit)
        f+=beta*fexit*wt
        # go up to the top: reflection-only from -wn
        wr, rw, okr = sample_reflection(-wn, n)
        beta=np.where(okr, beta*rw, 0)
        w=wr
        if not beta.any(): break
    return f.mean()
print("pbrt walk f at 45/45:", pbrt_f(45,45))
print("walk with consistent MIS f at 45/45:", pbrt_f(45, 45, consistent_mis=True))
