//! TEMPORARY STUB (replaced by the harvested file).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Float,
    Integer,
    Boolean,
    String,
    Transform,
    Point,
    Vector,
    Color,
    Texture,
    EmissiveTexture,
    UnboundedTexture,
    Volume,
    Object,
    Any,
}
#[derive(Clone, Copy, Debug)]
pub struct Property {
    pub name: &'static str,
    pub kind: Kind,
    pub default: Option<&'static str>,
    pub literal: Option<&'static str>,
    pub source: &'static str,
}
#[derive(Clone, Copy, Debug)]
pub struct Plugin {
    pub tag: &'static str,
    pub name: &'static str,
    pub source: &'static str,
    pub properties: &'static [Property],
    pub reads_any_property: bool,
}
pub static PLUGINS: &[Plugin] = &[];
pub fn plugin(tag: &str, name: &str) -> Option<&'static Plugin> {
    PLUGINS.iter().find(|p| p.tag == tag && p.name == name)
}
