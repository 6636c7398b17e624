//! External contours of coloured triangulations (Dorgerloh et al. §3). TODO(helper): issue 7.
