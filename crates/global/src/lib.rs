//! The global set-cover simplifier (Cohen et al. 1996, 5.3-5.4). Work in progress (issue 8).
#![forbid(unsafe_code)]
