//! Smallest enclosing disc and ball (Welzl 1991, move-to-front variant; expected linear time).
//!
//! TODO(helper): implement; see issue 2 item 3.
