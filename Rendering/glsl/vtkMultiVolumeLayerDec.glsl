// Strata multi-volume ray caster: the layers of the reduced volumes of this fragment (MIP,
// MinIP, average, additive), one each, premultiplied, at their depth t on the ray (a sentinel
// once composited or when the layer lies outside the fragment). A layer goes before the step
// that contains its depth; several go in the order of their depths.
float gLayerT[@L@] = float[@L@](@L0@);
vec4 gLayerC[@L@] = vec4[@L@](@L0V@);
// Front to back: every pending layer in front of `bound`, nearest first.
void strataLayersBefore(float bound, inout vec4 acc)
{
  for (int j = 0; j < @L@; ++j)
  {
    int m = -1;
    float tm = bound;
    for (int i = 0; i < @L@; ++i)
    {
      if (gLayerT[i] < tm)
      {
        tm = gLayerT[i];
        m = i;
      }
    }
    if (m < 0)
    {
      return;
    }
    acc += (1.0 - acc.a) * gLayerC[m];
    gLayerT[m] = 3.0e38;
  }
}
// Back to front: every pending layer at or behind `bound`, farthest first.
void strataLayersBehind(float bound, inout vec4 acc)
{
  for (int j = 0; j < @L@; ++j)
  {
    int m = -1;
    float tm = -3.0e38;
    for (int i = 0; i < @L@; ++i)
    {
      if (gLayerT[i] >= bound && gLayerT[i] > tm)
      {
        tm = gLayerT[i];
        m = i;
      }
    }
    if (m < 0)
    {
      return;
    }
    acc = gLayerC[m] + (1.0 - gLayerC[m].a) * acc;
    gLayerT[m] = -3.0e38;
  }
}
