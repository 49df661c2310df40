// Strata multi-volume ray caster: reduced volume @n@ of the fragment, read as a layer (its
// reduction pass wrote one state per ray into uLayer@n@_<ray>).
uniform sampler2D uTransfer@n@;
uniform vec3 uTableRange@n@;
uniform float uUnit@n@;
//STRATA::LayerSamplers::Dec
// The layer of state st: colour (premultiplied) and depth (3e38: none).
float strataLayer@n@(vec4 st, out vec4 color)
{
  //STRATA::LayerColor::Impl
}
