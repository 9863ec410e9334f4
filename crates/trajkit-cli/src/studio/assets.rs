//! The page's files, embedded in the binary at build time (the studio works offline and needs
//! nothing next to the executable). Source: `crates/trajkit-cli/web/`, one file per lesson
//! under `lessons/`, shared drawing and request helpers under `js/`.

/// A file: path under `/assets/` (or `index.html` for `/`), content type, bytes.
type Asset = (&'static str, &'static str, &'static [u8]);

macro_rules! asset {
    ($path:literal, $type:literal) => {
        (
            $path,
            $type,
            include_bytes!(concat!("../../web/", $path)) as &[u8],
        )
    };
}

const JS: &str = "text/javascript; charset=utf-8";

/// Every embedded file.
static ASSETS: &[Asset] = &[
    asset!("index.html", "text/html; charset=utf-8"),
    asset!("studio.css", "text/css; charset=utf-8"),
    asset!("favicon.svg", "image/svg+xml"),
    ("js/main.js", JS, include_bytes!("../../web/js/main.js")),
    ("js/api.js", JS, include_bytes!("../../web/js/api.js")),
    ("js/plot.js", JS, include_bytes!("../../web/js/plot.js")),
    ("js/ui.js", JS, include_bytes!("../../web/js/ui.js")),
    (
        "lessons/polynomials.js",
        JS,
        include_bytes!("../../web/lessons/polynomials.js"),
    ),
    (
        "lessons/catmull_rom.js",
        JS,
        include_bytes!("../../web/lessons/catmull_rom.js"),
    ),
    (
        "lessons/bspline.js",
        JS,
        include_bytes!("../../web/lessons/bspline.js"),
    ),
    (
        "lessons/profiles.js",
        JS,
        include_bytes!("../../web/lessons/profiles.js"),
    ),
    (
        "lessons/plan.js",
        JS,
        include_bytes!("../../web/lessons/plan.js"),
    ),
    (
        "lessons/primitives.js",
        JS,
        include_bytes!("../../web/lessons/primitives.js"),
    ),
    asset!("lessons/demos.json", "application/json"),
];

/// The content type and bytes of the file at `path`.
pub fn find(path: &str) -> Option<(&'static str, &'static [u8])> {
    ASSETS
        .iter()
        .find(|(p, _, _)| *p == path)
        .map(|(_, t, b)| (*t, *b))
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_lesson_is_embedded_and_unknown_paths_are_not() {
        for l in [
            "polynomials",
            "catmull_rom",
            "bspline",
            "profiles",
            "plan",
            "primitives",
        ] {
            let (t, b) = super::find(&format!("lessons/{l}.js")).expect(l);
            assert!(t.starts_with("text/javascript") && !b.is_empty());
        }
        assert!(super::find("../Cargo.toml").is_none());
        assert!(super::find("").is_none());
    }
}
