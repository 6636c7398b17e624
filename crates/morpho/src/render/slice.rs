//! Volume views: three orthogonal slices with colour maps (Hamann 1991 ch. 2). TODO(helper).
