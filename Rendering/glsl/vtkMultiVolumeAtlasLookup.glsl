// Strata multi-volume ray caster, the brick atlas's lookup of volume @n@ (written by
// strata::BrickAtlasTexture, which owns the atlas and the index textures): index coordinates (point
// (i, j, k) at (i, j, k)) to the entry f of the level-0 brick holding them (nearest, clamped to
// the table), resolved on the CPU: the atlas texel of the covering node's origin (xyz) and its
// scale 2^-level (w). The node's brick has a one-voxel border, so trilinear lookups are exact
// up to its faces. Transparent and slotless bricks (w < 0) read a value the transfer function
// makes transparent. Feedback rays check the node's level (the tag).
uniform sampler3D uIndex@n@;
uniform vec3 uTableDims@n@;   // level-0 bricks per axis
uniform vec3 uIndexExtent@n@; // their index-space extent: uTableDims (uBrickSize - 1)
uniform vec3 uIndexScale@n@;  // 1 / uIndexExtent
uniform float uEmptyScalar@n@; // a value the transfer function makes transparent
//STRATA::Decode::Dec
float strataScalarAt@n@(vec3 idx)
{
  vec3 x = clamp(idx, vec3(0.0), uIndexExtent@n@);
  vec4 f = textureLod(uIndex@n@, x * uIndexScale@n@, 0.0);
  //STRATA::FeedbackCheck::Impl
  float v = textureLod(uAtlas, (f.xyz + x * f.w) / uAtlasSize, 0.0).r@decode@;
  return f.w > 0.0 ? v : uEmptyScalar@n@;
}
