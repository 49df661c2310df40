tf = strataMedium@n@(p);
  //STRATA::Shade::Impl
  e += tf.rgb * tf.a;
  tau += tf.a;
