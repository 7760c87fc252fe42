//! Controlled simplification of genus (El-Sana and Varshney 1997). Work in progress (issue 7).
#![forbid(unsafe_code)]
