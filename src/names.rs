//! Names on the command line for small enums (cull modes, shading, depth
//! tests...): one macro gives each its `name`, `Display` and `FromStr`, so
//! a name is spelled in one place and an unknown one gets the list of
//! known ones.

/// Implements `name()`, `Display` and `FromStr` for a fieldless enum from
/// its variants' names: `named_enum!(Type, "what it is", Variant = "name", ...)`.
macro_rules! named_enum {
    ($ty:ident, $what:literal, $($variant:ident = $name:literal),+) => {
        impl $ty {
            /// The name used on the command line.
            pub fn name(self) -> &'static str {
                match self { $($ty::$variant => $name),+ }
            }
        }
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }
        impl std::str::FromStr for $ty {
            type Err = $crate::Error;
            fn from_str(s: &str) -> $crate::Result<Self> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    _ => Err($crate::Error::UnknownName {
                        what: $what,
                        name: s.to_string(),
                        known: [$($name),+].join(", "),
                    }),
                }
            }
        }
    };
}
pub(crate) use named_enum;
