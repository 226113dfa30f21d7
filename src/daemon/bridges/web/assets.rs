//! The page's files, embedded in the binary at build time (no build step, nothing fetched from the network):
//! each with the path it is served at and its content type.

/// One embedded file.
#[derive(Debug, Clone, Copy)]
pub struct Asset {
    pub path: &'static str,
    pub content_type: &'static str,
    pub body: &'static [u8],
}

const HTML: &str = "text/html; charset=utf-8";
const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";

/// Every file of the page.
pub const ASSETS: &[Asset] = &[
    Asset { path: "/", content_type: HTML, body: include_bytes!("page/index.html") },
    Asset { path: "/style.css", content_type: CSS, body: include_bytes!("page/style.css") },
    Asset { path: "/app.js", content_type: JS, body: include_bytes!("page/app.js") },
    Asset { path: "/views.js", content_type: JS, body: include_bytes!("page/views.js") },
    Asset { path: "/draw.js", content_type: JS, body: include_bytes!("page/draw.js") },
    Asset { path: "/favicon.svg", content_type: "image/svg+xml", body: include_bytes!("page/favicon.svg") },
];

/// The file served at `path` (`/index.html` is `/`).
pub fn find(path: &str) -> Option<&'static Asset> {
    let path = if path == "/index.html" { "/" } else { path };
    ASSETS.iter().find(|a| a.path == path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_page_names_only_files_that_are_served() {
        let html = std::str::from_utf8(find("/").unwrap().body).unwrap();
        for name in ["style.css", "app.js", "views.js", "draw.js", "favicon.svg"] {
            assert!(html.contains(&format!("\"/{name}\"")), "index.html does not load /{name}");
        }
        // Nothing from another host (the SVG namespace is a name, never fetched).
        for a in ASSETS {
            let text = String::from_utf8_lossy(a.body).replace("\"http://www.w3.org/2000/svg\"", "");
            assert!(!text.contains("http://") && !text.contains("https://"), "{} names another host", a.path);
        }
        assert_eq!(find("/index.html").unwrap().content_type, HTML);
        assert!(find("/../Cargo.toml").is_none());
    }
}
