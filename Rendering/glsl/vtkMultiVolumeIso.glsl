// Strata multi-volume ray caster: the contour surfaces of isosurface volume @n@ between two
// points, front (pa) to back (pb): every isovalue (ascending, at most 8) the scalar crosses
// between them, in the order the linear ramp crosses them, with the colour and opacity the
// transfer functions give the isovalue.
uniform sampler2D uTransfer@n@;
uniform vec3 uTableRange@n@;
uniform float uUnit@n@;
uniform float uIso@n@[8];
uniform int uNumIso@n@;
vec4 strataIso@n@(vec3 pa, vec3 pb)
{
  float sa = strataScalar@n@(pa);
  float sb = strataScalar@n@(pb);
  vec4 r = vec4(0.0);
  for (int j = 0; j < uNumIso@n@; ++j)
  {
    float v = uIso@n@[sb >= sa ? j : uNumIso@n@ - 1 - j];
    if ((sa >= v) != (sb >= v))
    {
      vec4 tf = textureLod(uTransfer@n@, vec2((v - uTableRange@n@.x) * uTableRange@n@.y + uTableRange@n@.z, 0.5), 0.0);
      float alpha = 1.0 - exp(-tf.a * uUnit@n@);
      //STRATA::IsoCrop::Impl
      vec3 rgb = tf.rgb;
      //STRATA::IsoShade::Impl
      r += (1.0 - r.a) * vec4(rgb * alpha, alpha);
    }
  }
  return r;
}
