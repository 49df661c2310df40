// Strata multi-volume ray caster: volume @n@'s independent components (vtkVolumeProperty's
// IndependentComponents on), each through its own transfer table (RGB and extinction per unit
// length at its own unit distance) and weight, as one medium of extinction
// sum_(w > 0) tau_i^2 / sum w_i tau_i and emission sum w_i c_i tau_i: vtkGPUVolumeRayCastMapper's
// per-sample rule (opacity sum a_i^2 / sum w_i a_i, colour sum w_i c_i a_i) in the limit of
// short steps, so that it does not depend on the sample distance.
uniform vec4 uWeights@n@;
//STRATA::ComponentTables::Dec
vec4 strataMedium@n@(vec3 p)
{
  vec4 s = strataComponents@n@(p);
  float weighted = 0.0;
  float squares = 0.0;
  vec3 e = vec3(0.0);
  vec4 tf = vec4(0.0);
  //STRATA::ComponentTables::Impl
  float tau = weighted > 0.0 ? squares / weighted : 0.0;
  return tau > 0.0 ? vec4(e / tau, tau) : vec4(0.0);
}
