// Strata multi-volume ray caster, a reduction pass: the layer state of each ray so far (read
// from the layer buffer under a texture barrier), and volume 0's opacity and normalised scalar.
uniform sampler2D uTransfer0;
uniform vec3 uTableRange0;
uniform float uUnit0;       // ScalarOpacityUnitDistance: the table holds extinction per unit
uniform vec2 uNormalize0;   // table range min, 1 / (max - min)
uniform vec2 uAverageRange0; // AverageIPScalarRange
vec4 gState = vec4(0.0);
float strataOpacity0(float s)
{
  float tau = textureLod(uTransfer0, vec2((s - uTableRange0.x) * uTableRange0.y + uTableRange0.z, 0.5), 0.0).a;
  return 1.0 - exp(-tau * uUnit0);
}
