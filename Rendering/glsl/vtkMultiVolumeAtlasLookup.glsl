// Strata multi-volume ray caster, the brick atlas's lookup of volume @n@ (written by
// vtkBrickAtlasTexture, which owns the atlas and the index textures): index coordinates (point
// (i, j, k) at (i, j, k)) to the level-0 brick b, its index entry e = (atlas slot, level of the
// cut node covering b), and the voxel's place in that node's brick, whose one-voxel border
// makes bilinear lookups exact up to its faces. Empty and slotless bricks read a value the
// transfer function makes transparent. Feedback rays check the entry's level (the tag).
uniform usampler3D uIndex@n@;
uniform vec3 uTableDims@n@;
uniform float uEmptyScalar@n@; // a value the transfer function makes transparent
float strataScalarAt@n@(vec3 idx)
{
  float S = uBrickSize - 1.0;
  vec3 x = clamp(idx, vec3(0.0), uTableDims@n@ * S);
  ivec3 b = min(ivec3(floor(x / S)), ivec3(uTableDims@n@) - 1);
  uvec4 e = texelFetch(uIndex@n@, b, 0);
  //STRATA::FeedbackCheck::Impl
  if (e.w >= 65534u)
  {
    return uEmptyScalar@n@;
  }
  vec3 t = vec3(e.xyz) * uBrickSize + x * exp2(-float(e.w)) - vec3(b >> int(e.w)) * S + 0.5;
  return texture(uAtlas, t / uAtlasSize).r;
}
