// Strata multi-volume ray caster, the lookup of volume @n@ without the atlas: one 3-D texture
// of the whole volume, point (i, j, k) at index coordinates (i, j, k).
uniform sampler3D uVolume@n@;
uniform vec3 uDims@n@;
//STRATA::Decode::Dec
float strataScalarAt@n@(vec3 idx)
{
  return textureLod(uVolume@n@, (idx + 0.5) / uDims@n@, 0.0).r@decode@;
}
