// The live VRML flavour (seed 000 §4.2): the file carries the simulation. The
// seed's three PROTOs — Garment (the cloth's IndexedFaceSet and its physical
// constants), ObjectCollider (a sphere or box the cloth hits) and
// SimulationScript (a TimeSensor driving a Script) — with the seed's Java
// engine replaced by ECMAScript, which every current VRML/X3D browser runs.
#include <algorithm>
#include <cmath>
#include <set>

#include "text.hpp"
#include "vgd/core/diagnostics.hpp"
#include "vgd/core/strings.hpp"
#include "vgd/io/vrml/vrml.hpp"

namespace vgd::io::vrml {

namespace {

// ---- the engine ------------------------------------------------------------------
// Mass-spring cloth (seed 000 §4.1): f_g = m g; f_v = -(k_v + α m) v; springs
// f_e = -[k_e (|l| - r) + k_d (l'·l)/|l|] l/|l| along every mesh edge (warp,
// weft or shear by the edge's direction in material space) and between the
// far corners of neighbouring triangles (bending, rest length of the two
// triangles unfolded flat); wind on each face f = c A ((w - v_face)·n) n with
// smooth gusts; symplectic Euler at the given step, then Provot's strain
// limit (edges longer than (1 + maxStrain) × rest pulled back, pins fixed,
// the correction / h added to the velocities as position-based dynamics
// does; seed 000 §4.1.1, Provot 1995), with a mass floor
// m_i >= max(h² Σk, 2 h Σk_d) that keeps it stable (Gershgorin); pins; contact
// with ellipsoids and boxes (pushed out to the surface, normal velocity
// reversed × bounce, tangential velocity × (1 - friction)).
// The engine's state lives in a closure: a browser may resolve a script's
// top-level names (its fields) through a slow scope, so they are read once
// per frame. Single quotes only: the text goes inside a VRML string.
constexpr std::string_view kScript = R"JS(
var E=(function(){
var n,X,V,X0,M,F,T,U,J,SA,SB,SR,SK,SD,NE,W,pin,cols,h,last=-1,t=0,ready=false,S3,MF3;
function uvOf(i,k){return U[J[i][k]];}
function setup(){
 var g=garment,P=g.coordinate,I=g.index,i,j,k,a,b;T=[];U=[];J=[];S3=SFVec3f;MF3=MFVec3f;
 if(P.length==0){
  var nu=g.warpParticles,nv=g.weftParticles,su=g.size.x/(nu-1),sv=g.size.y/(nv-1),o=g.translation,eu=g.uAxis,ev=g.vAxis;
  n=nu*nv;X=new Float64Array(3*n);
  for(j=0;j<nv;j++)for(i=0;i<nu;i++){k=j*nu+i;
   X[3*k]=o.x+i*su*eu.x+j*sv*ev.x;X[3*k+1]=o.y+i*su*eu.y+j*sv*ev.y;X[3*k+2]=o.z+i*su*eu.z+j*sv*ev.z;U.push([i*su,j*sv]);}
  for(j=0;j+1<nv;j++)for(i=0;i+1<nu;i++){a=j*nu+i;T.push([a,a+1,a+nu+1],[a,a+nu+1,a+nu]);}
  J=T;
 }else{
  n=P.length;X=new Float64Array(3*n);
  for(i=0;i<n;i++){X[3*i]=P[i].x;X[3*i+1]=P[i].y;X[3*i+2]=P[i].z;}
  var C=g.texCoord,K=g.texCoordIndex,ni=I.length,nk=K.length;for(i=0;i<C.length;i++)U.push([C[i].x,C[i].y]);
  for(i=0;i+3<ni;i+=4){T.push([I[i],I[i+1],I[i+2]]);J.push(nk?[K[i],K[i+1],K[i+2]]:[I[i],I[i+1],I[i+2]]);}
 }
 V=new Float64Array(3*n);X0=new Float64Array(X);F=new Float64Array(3*n);M=new Float64Array(n);
 h=integrationStep;
 var m=g.particleMass,dens=g.density,kd=g.elasticDampingConst,kw=g.warpElasticConst,kf=g.weftElasticConst,ks=g.shearElasticConst,
  bw=g.warpBendingElasticConst,bf=g.weftBendingElasticConst,Ks=new Float64Array(n),Kd=new Float64Array(n);
 for(i=0;i<T.length;i++){var p=uvOf(i,0),q=uvOf(i,1),r=uvOf(i,2),A=Math.abs((q[0]-p[0])*(r[1]-p[1])-(r[0]-p[0])*(q[1]-p[1]))/2;
  for(k=0;k<3;k++)M[T[i][k]]+=dens*A/3;}
 if(m>0)M.fill(m);
 var S=[],S2=[],E={};
 function spring(a,b,r,k,bend){(bend?S2:S).push([a,b,r,k]);Ks[a]+=k;Ks[b]+=k;Kd[a]+=kd;Kd[b]+=kd;}
 for(i=0;i<T.length;i++)for(k=0;k<3;k++){
  a=T[i][k];b=T[i][(k+1)%3];var key=a<b?a*n+b:b*n+a,pa=uvOf(i,k),pb=uvOf(i,(k+1)%3),du=pb[0]-pa[0],dv=pb[1]-pa[1],L=Math.hypot(du,dv);
  var o=uvOf(i,(k+2)%3),s=((o[0]-pa[0])*du+(o[1]-pa[1])*dv)/L,d=Math.abs((o[0]-pa[0])*dv-(o[1]-pa[1])*du)/L;
  if(!(key in E)){E[key]=[T[i][(k+2)%3],a<b?s:L-s,d,du,dv];
   spring(a,b,L,Math.abs(dv)<0.4*Math.abs(du)?kw:Math.abs(du)<0.4*Math.abs(dv)?kf:ks);}
  else{var e=E[key],c=T[i][(k+2)%3];if(e[0]!=c){var s2=a<b?s:L-s;
   spring(e[0],c,Math.hypot(e[1]-s2,e[2]+d),Math.abs(e[4])<0.4*Math.abs(e[3])?bf:bw,1);}}
 }
 NE=S.length;S=S.concat(S2);var N=S.length;SA=new Int32Array(N);SB=new Int32Array(N);SR=new Float64Array(N);SK=new Float64Array(N);
 for(i=0;i<N;i++){SA[i]=S[i][0];SB[i]=S[i][1];SR[i]=S[i][2];SK[i]=S[i][3];}
 SD=kd;
 for(i=0;i<n;i++)M[i]=Math.max(M[i],h*h*Ks[i],2*h*Kd[i],1e-6);
 var pp=g.pinned;pin=[];W=new Float64Array(n).fill(1);for(i=0;i<pp.length;i++)if(pp[i]>=0&&pp[i]<n){pin.push(pp[i]);W[pp[i]]=0;}
 var cl=colliders;cols=[];for(i=0;i<cl.length;i++){var c=cl[i];if(c)cols.push([c.shape,c.translation.x,c.translation.y,c.translation.z,c.size.x,c.size.y,c.size.z,c.friction,c.bounce]);}
 var ci=new MFInt32();ci.length=4*T.length;for(i=0;i<T.length;i++){ci[4*i]=T[i][0];ci[4*i+1]=T[i][1];ci[4*i+2]=T[i][2];ci[4*i+3]=-1;}coordIndex_changed=ci;
 if(P.length==0){var tc=[];for(i=0;i<n;i++)tc.push(new SFVec2f(U[i][0],U[i][1]));texCoord_changed=new MFVec2f(...tc);}
 var ti=new MFInt32();ti.length=4*J.length;for(i=0;i<J.length;i++){ti[4*i]=J[i][0];ti[4*i+1]=J[i][1];ti[4*i+2]=J[i][2];ti[4*i+3]=-1;}texCoordIndex_changed=ti;
 ready=true;
}
function collide(i){
 for(var c=0;c<cols.length;c++){var C=cols[c],q=[X[3*i]-C[1],X[3*i+1]-C[2],X[3*i+2]-C[3]],nx=0,ny=0,nz=0;
  if(C[0]==0){var a=q[0]/C[4],b=q[1]/C[5],e=q[2]/C[6],d=Math.sqrt(a*a+b*b+e*e);if(d>=1||d==0)continue;
   X[3*i]=C[1]+q[0]/d;X[3*i+1]=C[2]+q[1]/d;X[3*i+2]=C[3]+q[2]/d;nx=a/C[4];ny=b/C[5];nz=e/C[6];}
  else{var best=1e9,ax=-1;for(var k=0;k<3;k++){var p=C[4+k]-Math.abs(q[k]);if(p<=0){ax=-1;break;}if(p<best){best=p;ax=k;}}
   if(ax<0)continue;var sg=q[ax]<0?-1:1;X[3*i+ax]=C[1+ax]+sg*C[4+ax];if(ax==0)nx=sg;else if(ax==1)ny=sg;else nz=sg;}
  var l=Math.hypot(nx,ny,nz);nx/=l;ny/=l;nz/=l;var vn=V[3*i]*nx+V[3*i+1]*ny+V[3*i+2]*nz;
  var tx=V[3*i]-vn*nx,ty=V[3*i+1]-vn*ny,tz=V[3*i+2]-vn*nz,f=1-C[7];if(vn<0)vn=-vn*C[8];
  V[3*i]=tx*f+vn*nx;V[3*i+1]=ty*f+vn*ny;V[3*i+2]=tz*f+vn*nz;}
}
function step(P){
 var i,k,gx=P[0],gy=P[1],gz=P[2],kv=P[3],al=P[4],tu=P[8],cw=P[9]/6;
 for(i=0;i<n;i++){var m=M[i],c=kv+al*m;F[3*i]=m*gx-c*V[3*i];F[3*i+1]=m*gy-c*V[3*i+1];F[3*i+2]=m*gz-c*V[3*i+2];}
 for(k=0;k<SA.length;k++){var a=3*SA[k],b=3*SB[k],dx=X[a]-X[b],dy=X[a+1]-X[b+1],dz=X[a+2]-X[b+2],L=Math.sqrt(dx*dx+dy*dy+dz*dz);if(L<1e-9)continue;
  dx/=L;dy/=L;dz/=L;var s=SK[k]*(L-SR[k])+SD*((V[a]-V[b])*dx+(V[a+1]-V[b+1])*dy+(V[a+2]-V[b+2])*dz);
  F[a]-=s*dx;F[a+1]-=s*dy;F[a+2]-=s*dz;F[b]+=s*dx;F[b+1]+=s*dy;F[b+2]+=s*dz;}
 var gu=1+tu*(0.6*Math.sin(6.2832*t)+0.4*Math.sin(17.1*t+1.3)),wx=P[5]*gu,wy=P[6]*gu,wz=P[7]*gu;
 if(cw!=0)for(k=0;k<T.length;k++){var A=3*T[k][0],B=3*T[k][1],C=3*T[k][2];
  var ux=X[B]-X[A],uy=X[B+1]-X[A+1],uz=X[B+2]-X[A+2],vx=X[C]-X[A],vy=X[C+1]-X[A+1],vz=X[C+2]-X[A+2];
  var cx=uy*vz-uz*vy,cy=uz*vx-ux*vz,cz=ux*vy-uy*vx,l=Math.sqrt(cx*cx+cy*cy+cz*cz);if(l<1e-12)continue;
  var r=((wx-(V[A]+V[B]+V[C])/3)*cx+(wy-(V[A+1]+V[B+1]+V[C+1])/3)*cy+(wz-(V[A+2]+V[B+2]+V[C+2])/3)*cz)/l,f=cw*r;
  cx*=f;cy*=f;cz*=f;F[A]+=cx;F[A+1]+=cy;F[A+2]+=cz;F[B]+=cx;F[B+1]+=cy;F[B+2]+=cz;F[C]+=cx;F[C+1]+=cy;F[C+2]+=cz;}
 for(i=0;i<n;i++){var w=h/M[i];for(k=3*i;k<3*i+3;k++){V[k]+=w*F[k];X[k]+=h*V[k];}}
 for(k=0;k<pin.length;k++){i=3*pin[k];X[i]=X0[i];X[i+1]=X0[i+1];X[i+2]=X0[i+2];V[i]=V[i+1]=V[i+2]=0;}
 var mx=P[10];if(mx>0)for(k=0;k<NE;k++){var a=SA[k],b=SB[k],A=3*a,B=3*b,dx=X[B]-X[A],dy=X[B+1]-X[A+1],dz=X[B+2]-X[A+2],L=Math.sqrt(dx*dx+dy*dy+dz*dz),R=SR[k]*(1+mx),ws=W[a]+W[b];
  if(L>R&&ws>0){var c=(L-R)/(L*ws),ca=c*W[a],cb=c*W[b],qa=ca/h,qb=cb/h;X[A]+=dx*ca;X[A+1]+=dy*ca;X[A+2]+=dz*ca;X[B]-=dx*cb;X[B+1]-=dy*cb;X[B+2]-=dz*cb;
   V[A]+=dx*qa;V[A+1]+=dy*qa;V[A+2]+=dz*qa;V[B]-=dx*qb;V[B+1]-=dy*qb;V[B+2]-=dz*qb;}}
 if(cols.length)for(i=0;i<n;i++)collide(i);
 t+=h;
}
return function(now){
 if(!ready)setup();
 var dt=last<0?h:Math.min(now-last,maxFrameTime);last=now;
 var P=[gravity.x,gravity.y,gravity.z,viscosity,viscosityRate,wind.x,wind.y,wind.z,windTurbulence,windCoefficient,maxStrain];
 for(var s=Math.min(Math.ceil(dt/h),maxSteps);s>0;s--)step(P);
 var out=new MF3();out.length=n;for(var i=0;i<n;i++)out[i]=new S3(X[3*i],X[3*i+1],X[3*i+2]);coord_changed=out;
};
})();
function tick(now){E(now);}
)JS";

// The three PROTOs. Field names follow the seed (camel case for VRML style).
constexpr std::string_view kProtos = R"VRML(
# Garment: particles (m), triangles, material coordinates (m), pins; springs in N/m,
# damping kg/s, mass kg (0: density kg/m2 x area). No coordinate: the script makes a
# warpParticles x weftParticles grid of size (m) at translation along uAxis, vAxis.
PROTO Garment [
 exposedField MFVec3f coordinate []
 exposedField MFInt32 index []
 exposedField MFVec2f texCoord []
 exposedField MFInt32 texCoordIndex []
 exposedField MFInt32 pinned []
 exposedField SFInt32 warpParticles 30
 exposedField SFInt32 weftParticles 30
 exposedField SFVec2f size 1.5 1
 exposedField SFVec3f translation 0 0 0
 exposedField SFVec3f uAxis 1 0 0
 exposedField SFVec3f vAxis 0 -1 0
 exposedField SFFloat particleMass 0.1
 exposedField SFFloat density 0.2
 exposedField SFFloat warpElasticConst 1800
 exposedField SFFloat weftElasticConst 1800
 exposedField SFFloat shearElasticConst 400
 exposedField SFFloat warpBendingElasticConst 400
 exposedField SFFloat weftBendingElasticConst 400
 exposedField SFFloat elasticDampingConst 0.1
 exposedField SFNode appearance NULL
 field SFFloat creaseAngle 3.1
 eventIn MFInt32 set_coordIndex
 eventIn MFInt32 set_texCoordIndex
] {
 Shape {
  appearance IS appearance
  geometry IndexedFaceSet {
   coord Coordinate { point IS coordinate }
   texCoord TextureCoordinate { point IS texCoord }
   set_coordIndex IS set_coordIndex
   set_texCoordIndex IS set_texCoordIndex
   solid FALSE
   creaseAngle IS creaseAngle
  }
 }
}
# ObjectCollider: shape 0 an ellipsoid (size = radii, m), 1 a box (size = half
# extents); friction and bounce of contacts; display -1 hides it.
PROTO ObjectCollider [
 exposedField SFInt32 shape 0
 exposedField SFVec3f translation 0 0 0
 exposedField SFVec3f size 0.1 0.1 0.1
 exposedField SFFloat friction 0.5
 exposedField SFFloat bounce 0.3
 exposedField SFInt32 display 0
 exposedField SFNode appearance NULL
] {
 Transform { translation IS translation scale IS size
  children Switch { whichChoice IS display choice Switch { whichChoice IS shape choice [
   Shape { appearance IS appearance geometry Sphere { radius 1 } }
   Shape { appearance IS appearance geometry Box { size 2 2 2 } }
  ] } }
 }
}
# SimulationScript: a TimeSensor ticks the Script, which advances the garment (SI
# units: gravity m/s2, viscosity N s/m, viscosityRate 1/s, wind m/s, windCoefficient
# N s/m3, steps s; maxStrain: Provot's limit) and sends its coordinates every frame.
PROTO SimulationScript [
 field SFNode garment NULL
 field MFNode colliders []
 field SFVec3f gravity 0 -9.81 0
 field SFFloat viscosity 0.2
 field SFFloat viscosityRate 0
 field SFVec3f wind 10 10 -100
 field SFFloat windCoefficient 40
 field SFFloat windTurbulence 0.1
 field SFFloat maxStrain 0.1
 field SFFloat integrationStep 0.0025
 field SFFloat maxFrameTime 0.04
 field SFInt32 maxSteps 40
 exposedField SFBool enabled TRUE
 eventOut MFVec3f coord_changed
 eventOut MFInt32 coordIndex_changed
 eventOut MFVec2f texCoord_changed
 eventOut MFInt32 texCoordIndex_changed
] {
 Group { children [
  DEF Clock TimeSensor { loop TRUE enabled IS enabled }
  DEF Engine Script {
   mustEvaluate TRUE
   eventIn SFTime tick
   field SFNode garment IS garment
   field MFNode colliders IS colliders
   field SFVec3f gravity IS gravity
   field SFFloat viscosity IS viscosity
   field SFFloat viscosityRate IS viscosityRate
   field SFVec3f wind IS wind
   field SFFloat windCoefficient IS windCoefficient
   field SFFloat windTurbulence IS windTurbulence
   field SFFloat maxStrain IS maxStrain
   field SFFloat integrationStep IS integrationStep
   field SFFloat maxFrameTime IS maxFrameTime
   field SFInt32 maxSteps IS maxSteps
   eventOut MFVec3f coord_changed IS coord_changed
   eventOut MFInt32 coordIndex_changed IS coordIndex_changed
   eventOut MFVec2f texCoord_changed IS texCoord_changed
   eventOut MFInt32 texCoordIndex_changed IS texCoordIndex_changed
   url "javascript:@SCRIPT@"
  }
 ] }
 ROUTE Clock.time TO Engine.tick
}
)VRML";

void vec3(std::string& o, const std::array<double, 3>& v, int decimals = 4) {
  append_number(o, v[0], decimals), o += ' ', append_number(o, v[1], decimals), o += ' ';
  append_number(o, v[2], decimals);
}

std::string protos() {
  std::string p(kProtos);
  // The engine without its indentation, escaped for a VRML string.
  std::string js;
  for (const auto& line : split(live_script_source(), '\n'))
    if (!trim(line).empty()) js += std::string(trim(line)) + "\n";
  std::string script = detail::quoted(js);
  script = script.substr(1, script.size() - 2);  // escaped, without the quotes
  p.replace(p.find("@SCRIPT@"), 8, script);
  return p;
}

// Fields whose value differs from the PROTO's default (the seed's flag, LiveOptions{}).
void scalar_field(std::string& s, const char* name, double v, double fallback, int decimals = 6) {
  if (v == fallback) return;
  s += std::string("  ") + name + " ";
  append_number(s, v, decimals);
  s += "\n";
}

void vector_field(std::string& s, const char* name, const std::array<double, 3>& v,
                  const std::array<double, 3>& fallback, int decimals = 4) {
  if (v == fallback) return;
  s += std::string("  ") + name + " ";
  vec3(s, v, decimals);
  s += "\n";
}

// The Garment instance's physical fields.
std::string physics_fields(const LiveOptions& o) {
  const LiveOptions d;
  std::string s;
  scalar_field(s, "particleMass", std::max(0.0, o.particle_mass), d.particle_mass);
  scalar_field(s, "density", o.density, d.density);
  scalar_field(s, "warpElasticConst", o.warp_constant, d.warp_constant);
  scalar_field(s, "weftElasticConst", o.weft_constant, d.weft_constant);
  scalar_field(s, "shearElasticConst", o.shear_constant, d.shear_constant);
  scalar_field(s, "warpBendingElasticConst", o.warp_bend_constant, d.warp_bend_constant);
  scalar_field(s, "weftBendingElasticConst", o.weft_bend_constant, d.weft_bend_constant);
  scalar_field(s, "elasticDampingConst", o.spring_damping, d.spring_damping);
  return s;
}

std::string pinned_field(const std::vector<int>& pinned) {
  std::string s = "  pinned [";
  for (std::size_t k = 0; k < pinned.size(); ++k) s += (k % 20 == 0 ? "\n    " : " ") + std::to_string(pinned[k]);
  return s + " ]\n";
}

// ObjectCollider instances and the SimulationScript instance with its routes.
std::string colliders_and_script(const LiveOptions& o, const std::string& garment_def) {
  const LiveOptions d;
  std::string s;
  for (std::size_t k = 0; k < o.colliders.size(); ++k) {
    const auto& c = o.colliders[k];
    s += "DEF Collider" + std::to_string(k + 1) + " ObjectCollider {\n  shape ";
    s += c.shape == Collider::Shape::box ? "1" : "0";
    s += "\n  translation ", vec3(s, c.centre);
    s += "\n  size ", vec3(s, c.size);
    s += "\n";
    scalar_field(s, "friction", c.friction, 0.5, 3);
    scalar_field(s, "bounce", c.bounce, 0.3, 3);
    if (!c.visible) s += "  display -1\n";
    s += k == 0 ? "  appearance DEF ColliderLook " + detail::appearance(Rgba{0.55, 0.55, 0.58, 1.0}, 2) + "\n}\n"
                : "  appearance USE ColliderLook\n}\n";
  }
  s += "DEF Simulation SimulationScript {\n  garment USE " + garment_def + "\n  colliders [";
  for (std::size_t k = 0; k < o.colliders.size(); ++k) s += " USE Collider" + std::to_string(k + 1);
  s += " ]\n";
  vector_field(s, "gravity", o.gravity, d.gravity);
  scalar_field(s, "viscosity", o.viscosity, d.viscosity);
  scalar_field(s, "viscosityRate", o.viscosity_rate, d.viscosity_rate);
  vector_field(s, "wind", o.wind, d.wind, 3);
  scalar_field(s, "windCoefficient", o.wind_coefficient, d.wind_coefficient, 4);
  scalar_field(s, "windTurbulence", o.wind_turbulence, d.wind_turbulence, 3);
  scalar_field(s, "maxStrain", o.max_strain, d.max_strain, 4);
  scalar_field(s, "integrationStep", o.step, d.step);
  scalar_field(s, "maxFrameTime", o.max_frame_time, d.max_frame_time, 4);
  scalar_field(s, "maxSteps", o.max_steps, d.max_steps, 0);
  s += "}\n";
  // The seed's event sequence: the script's outputs drive the garment's geometry.
  s += "ROUTE Simulation.coord_changed TO " + garment_def + ".set_coordinate\n";
  s += "ROUTE Simulation.coordIndex_changed TO " + garment_def + ".set_coordIndex\n";
  s += "ROUTE Simulation.texCoord_changed TO " + garment_def + ".set_texCoord\n";
  s += "ROUTE Simulation.texCoordIndex_changed TO " + garment_def + ".set_texCoordIndex\n";
  return s;
}

}  // namespace

std::string_view live_script_source() { return kScript; }

std::string live_vrml(const Garment& g, const LiveOptions& options, int frame) {
  g.validate();
  const int decimals = detail::checked_decimals(options.precision);
  if (frame < 0) frame = g.frames.count() - 1;
  if (frame >= g.frames.count()) throw Error(g.name, "", "frame " + std::to_string(frame) + " does not exist");
  const auto& x = g.frames.positions[frame];
  // Welded: merged particles are one particle of the live cloth.
  const OutputMesh mesh = output_mesh(g.cloth, true);
  const double h = median_edge_length(g.cloth);
  const double crease = options.crease_angle >= 0 ? options.crease_angle : crease_angle(h);
  std::vector<std::array<int, 3>> faces, tex;
  for (const auto& p : mesh.pieces) {
    faces.insert(faces.end(), p.coord.begin(), p.coord.end());
    tex.insert(tex.end(), p.tex.begin(), p.tex.end());
  }
  // Pins in output vertices.
  std::set<int> pins;
  for (int p : options.pinned)
    if (p >= 0 && p < g.cloth.num_particles()) pins.insert(mesh.particle_vertex[p]);

  std::string o = detail::preamble(
      g.name, {"vgd live garment '" + g.name + "': the viewer simulates it (seed 000 §4.2, docs/vrml.md)",
               std::to_string(mesh.vertex_particle.size()) + " particles, " + std::to_string(faces.size()) +
                   " triangles, " + std::to_string(pins.size()) + " pinned, " +
                   std::to_string(options.colliders.size()) + " colliders; creaseAngle " + format_fixed(crease, 2) +
                   " rad"},
      detail::garment_box(g, frame));
  o += protos();
  // One Garment for the whole cloth, in the first piece's look.
  o += "DEF Cloth Garment {\n  coordinate ";
  detail::append_points(o, x, mesh.vertex_particle, decimals, 4);
  o += "\n  index ";
  detail::append_faces(o, faces, 4);
  o += "\n  texCoord ";
  detail::append_uv(o, g.cloth.uv, decimals, 4);
  o += "\n  texCoordIndex ";
  detail::append_faces(o, tex, 4);
  o += "\n" + pinned_field({pins.begin(), pins.end()});
  o += physics_fields(options);
  o += "  creaseAngle ", append_number(o, crease, 3);
  o += "\n  appearance " + detail::appearance(g.look(0), 2) + "\n}\n";
  if (options.body && g.body) o += detail::body_shape(*g.body, 3);
  o += colliders_and_script(options, "Cloth");
  return o;
}

std::string live_flag_vrml(const FlagOptions& f) {
  VGD_ASSERT(f.warp_particles >= 2 && f.weft_particles >= 2, "a flag needs at least 2 x 2 particles");
  LiveOptions live = f.live;
  // The seed's flag hangs on its staff by the two corners of its first column.
  live.pinned = {0, (f.weft_particles - 1) * f.warp_particles};
  if (f.staff) {
    const double staff_r = 0.025;
    // The staff: a thin box just behind the pinned edge, from the ground to above the flag.
    Collider staff;
    staff.shape = Collider::Shape::box;
    const double top = f.origin[1] + 0.15;
    staff.centre = {f.origin[0] - f.u_axis[0] * staff_r * 1.6, 0.5 * top, f.origin[2] - f.u_axis[2] * staff_r * 1.6};
    staff.size = {staff_r, 0.5 * top, staff_r};
    // A ball on top of the staff.
    Collider ball;
    ball.centre = {staff.centre[0], top + 0.06, staff.centre[2]};
    ball.size = {0.07, 0.07, 0.07};
    live.colliders.insert(live.colliders.begin(), {staff, ball});
  }
  detail::Box box;
  box.add(f.origin[0], f.origin[1], f.origin[2]);
  for (int k = 0; k < 3; ++k) {
    box.add(f.origin[0] + f.size[0] * f.u_axis[0] + f.size[1] * f.v_axis[0],
            f.origin[1] + f.size[0] * f.u_axis[1] + f.size[1] * f.v_axis[1],
            f.origin[2] + f.size[0] * f.u_axis[2] + f.size[1] * f.v_axis[2]);
  }
  const double h = std::min(f.size[0] / (f.warp_particles - 1), f.size[1] / (f.weft_particles - 1));
  const double crease = live.crease_angle >= 0 ? live.crease_angle : crease_angle(h);

  std::string o = detail::preamble(
      "flag", {"vgd live flag (seed 000 §4.2): a pinned rectangle of cloth in the wind, simulated by the viewer",
               std::to_string(f.warp_particles) + " x " + std::to_string(f.weft_particles) +
                   " particles generated by the script; docs/vrml.md"},
      box, true);
  o += protos();
  o += "DEF Flag Garment {\n";
  scalar_field(o, "warpParticles", f.warp_particles, 30, 0);
  scalar_field(o, "weftParticles", f.weft_particles, 30, 0);
  if (f.size != std::array<double, 2>{1.5, 1.0})
    o += "  size ", append_number(o, f.size[0], 4), o += ' ', append_number(o, f.size[1], 4), o += "\n";
  vector_field(o, "translation", f.origin, {0, 0, 0});
  vector_field(o, "uAxis", f.u_axis, {1, 0, 0});
  vector_field(o, "vAxis", f.v_axis, {0, -1, 0});
  o += pinned_field(live.pinned);
  o += physics_fields(live);
  o += "  creaseAngle ", append_number(o, crease, 3);
  o += "\n  appearance " + detail::appearance(f.colour, 2) + "\n}\n";
  o += colliders_and_script(live, "Flag");
  return o;
}

std::vector<Collider> body_colliders(const Garment& g, int bands, double clearance) {
  std::vector<Collider> out;
  if (!g.body || g.frames.positions.empty() || bands < 1) return out;
  const auto& x = g.frames.positions.back();
  double ylo = 1e300, yhi = -1e300;
  for (std::size_t i = 1; i < x.size(); i += 3) ylo = std::min<double>(ylo, x[i]), yhi = std::max<double>(yhi, x[i]);
  const double dy = (yhi - ylo) / bands;
  if (!(dy > 0)) return out;
  for (int b = 0; b < bands; ++b) {
    const double y0 = ylo + b * dy, y1 = y0 + dy;
    // The garment's horizontal extent in the band, then the body inside it.
    detail::Box gb, bb;
    for (std::size_t i = 0; i + 2 < x.size(); i += 3)
      if (x[i + 1] >= y0 && x[i + 1] <= y1) gb.add(x[i], x[i + 1], x[i + 2]);
    if (gb.empty()) continue;
    int inside = 0;
    for (const auto& v : g.body->vertices)
      if (v[1] >= y0 && v[1] <= y1 && v[0] >= gb.lo[0] && v[0] <= gb.hi[0] && v[2] >= gb.lo[2] && v[2] <= gb.hi[2])
        bb.add(v[0], v[1], v[2]), ++inside;
    if (inside < 8) continue;
    Collider c;
    c.centre = {0.5 * (bb.lo[0] + bb.hi[0]), 0.5 * (y0 + y1), 0.5 * (bb.lo[2] + bb.hi[2])};
    c.size = {std::max(0.01, 0.5 * (bb.hi[0] - bb.lo[0]) + clearance), 1.5 * dy,
              std::max(0.01, 0.5 * (bb.hi[2] - bb.lo[2]) + clearance)};
    c.visible = false;  // inside the body, which is drawn
    out.push_back(c);
  }
  return out;
}

std::vector<int> top_particles(const Garment& g, double band, int frame) {
  std::vector<int> out;
  if (g.frames.positions.empty()) return out;
  const auto& x = frame < 0 || frame >= g.frames.count() ? g.frames.positions.back() : g.frames.positions[frame];
  double top = -1e300;
  for (std::size_t i = 1; i < x.size(); i += 3) top = std::max<double>(top, x[i]);
  for (std::size_t i = 1; i < x.size(); i += 3)
    if (x[i] >= top - band) out.push_back(static_cast<int>(i / 3));
  return out;
}

}  // namespace vgd::io::vrml
