//! Tests of the outputs of a run ([`crate::files`]): no run loses or changes a file it should
//! not. Each case is run through [`crate::run::run`] with the flat-colour renderer of the
//! common tests, with exact messages; a full disk is simulated by [`files::SPACE_LEFT`].

use std::path::{Path, PathBuf};

use crate::cli::{self, Command, Options};
use crate::common_tests::{one_object, scratch, Flat};
use crate::files::{self, Kind, Transaction};
use crate::run;

fn render_args(args: &str) -> Options {
    let args: Vec<String> = args.split_whitespace().map(String::from).collect();
    match cli::parse::<()>(&args).unwrap() {
        Command::Render(o, ()) => o,
        other => panic!("{other:?}"),
    }
}

/// Runs the flat renderer quietly with `args`.
fn run(args: &str) -> Result<(), String> {
    run::run(&Flat, &render_args(&format!("{args} --quiet")))
}

/// The names in `dir`, hidden ones (temporaries) included, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A scratch directory with a tiny scene `tiny.toml` (8 × 6 pixels) and existing files.
fn setup(name: &str, existing: &[&str]) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let tiny = dir.join("tiny.toml");
    std::fs::write(&tiny, one_object("", "", "", "", "type = \"diffuse\"")).unwrap();
    for f in existing {
        std::fs::write(dir.join(f), OLD).unwrap();
    }
    (dir, tiny)
}

const OLD: &[u8] = b"an existing, valid file";

fn canonical(dir: &Path) -> PathBuf {
    dir.canonicalize().unwrap()
}

/// Output names are checked before rendering: extensions, directories, two outputs on one file
/// under two names, `--frames` or several scenes with a file name, and `--out .png`.
#[test]
fn bad_output_names_are_refused_before_rendering() {
    let (dir, tiny) = setup("names", &["a.png", "a.pfm"]);
    let (d, t) = (dir.display(), tiny.display());
    let c = canonical(&dir);
    for (args, expected) in [
        (format!("{t} --out {d}/a.png --pfm {d}/a.png"), format!("--pfm {d}/a.png: expected a file name ending in .pfm")),
        (format!("{t} --out {d}/a.pfm --pfm {d}/sub/../a.pfm"), format!("{d}/a.pfm and {d}/sub/../a.pfm are the same file ({}): refusing to write two outputs on it", c.join("a.pfm").display())),
        (format!("{t} --out {d}/a.pfm --pfm {d}/./a.pfm"), format!("{d}/a.pfm and {d}/./a.pfm are the same file ({}): refusing to write two outputs on it", c.join("a.pfm").display())),
        (format!("{t} {t} --out {d}"), format!("{d}/tiny.png and {d}/tiny.png are the same file ({}): refusing to write two outputs on it", c.join("tiny.png").display())),
        (format!("{t} --out {d}/a.jpg"), format!("--out {d}/a.jpg: expected a file name ending in .png or .pfm, or a directory")),
        (format!("{t} --out {d}/a.png/b.png"), format!("--out {d}/a.png/b.png: cannot create the directory {d}/a.png: {} is not a directory", c.join("a.png").display())),
        (format!("{t} --out {d}/.png"), format!("--out {d}/.png: expected a file name before the extension .png")),
        (format!("{t} --frames 2 --out {d}/x.png"), format!("--out {d}/x.png: names a file, but the frames of --frames go into a directory: give a directory")),
        (format!("{t} {t} --out {d}/shots.png"), format!("--out {d}/shots.png: names a file, but the pictures of several scenes go into a directory: give a directory")),
    ] {
        assert_eq!(run(&args), Err(expected), "{args}");
    }
    #[cfg(target_os = "linux")]
    assert_eq!(
        run(&format!("{t} --out /dev/full")),
        Err(
            "--out /dev/full: not a directory (give a directory, or one scene and a file name \
             ending in .png or .pfm)"
                .into()
        )
    );
    // Nothing was created or changed.
    assert_eq!(listing(&dir), ["a.pfm", "a.png", "tiny.toml"]);
    assert_eq!(std::fs::read(dir.join("a.png")).unwrap(), OLD);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A disk that fills up after the PNG: the PFM fails, the old PNG and PFM stay, no temporary is
/// left, and no new directory is created; with room, both are replaced whole.
#[test]
fn a_full_disk_changes_nothing() {
    let (dir, tiny) = setup("full", &["keep.png", "keep.pfm"]);
    let (d, t) = (dir.display(), tiny.display());
    // An 8 × 6 PNG takes about 100 bytes; the PFM 12 + 8·6·12 = 588.
    files::SPACE_LEFT.with(|s| s.set(Some(300)));
    let result = run(&format!("{t} --out {d}/keep.png --pfm {d}/new/keep.pfm"));
    files::SPACE_LEFT.with(|s| s.set(None));
    assert_eq!(
        result,
        Err(format!(
            "cannot write {d}/new/keep.pfm: No space left on device (a test's full disk)"
        ))
    );
    assert_eq!(listing(&dir), ["keep.pfm", "keep.png", "tiny.toml"]);
    assert_eq!(std::fs::read(dir.join("keep.png")).unwrap(), OLD);
    // With room: both land, the directory is made.
    assert_eq!(
        run(&format!("{t} --out {d}/keep.png --pfm {d}/new/keep.pfm")),
        Ok(())
    );
    assert_eq!(
        image::open(dir.join("keep.png"))
            .unwrap()
            .to_rgb8()
            .dimensions(),
        (8, 6)
    );
    assert!(std::fs::read(dir.join("new/keep.pfm"))
        .unwrap()
        .starts_with(b"PF\n8 6\n"));
    assert_eq!(listing(&dir), ["keep.pfm", "keep.png", "new", "tiny.toml"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--frames`: a disk that fills up during the animation keeps every old frame and GIF; a
/// successful one streams every frame into the GIF.
#[test]
fn an_animation_lands_whole_or_not_at_all() {
    use image::AnimationDecoder;
    let (dir, tiny) = setup("frames", &[]);
    let out = dir.join("anim");
    std::fs::create_dir(&out).unwrap();
    let names = [
        "tiny.gif",
        "tiny_0000.png",
        "tiny_0001.png",
        "tiny_0002.png",
    ];
    for n in names {
        std::fs::write(out.join(n), OLD).unwrap();
    }
    let args = format!("{} --frames 3 --out {}", tiny.display(), out.display());
    // Room for about two frames.
    files::SPACE_LEFT.with(|s| s.set(Some(250)));
    let result = run(&args);
    files::SPACE_LEFT.with(|s| s.set(None));
    assert!(
        result
            .as_ref()
            .is_err_and(|e| e.ends_with("No space left on device (a test's full disk)")),
        "{result:?}"
    );
    assert_eq!(listing(&out), names);
    assert!(names
        .iter()
        .all(|n| std::fs::read(out.join(n)).unwrap() == OLD));
    assert_eq!(run(&args), Ok(()));
    assert_eq!(listing(&out), names);
    let gif = std::io::BufReader::new(std::fs::File::open(out.join("tiny.gif")).unwrap());
    let frames = image::codecs::gif::GifDecoder::new(gif)
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 3);
    assert_eq!(frames[0].buffer().dimensions(), (8, 6));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A scene that fails to load, after one that loads, is reported before anything is rendered:
/// the first scene's old picture stays.
#[test]
fn an_error_in_any_scene_comes_before_any_write() {
    let (dir, tiny) = setup("plan", &["tiny.png"]);
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[camera]\n").unwrap();
    let (d, t, b) = (dir.display(), tiny.display(), bad.display());
    assert_eq!(
        run(&format!("{t} {b} --out {d}")),
        Err(format!(
            "{b}: line 1, field camera.position: missing field `position`"
        ))
    );
    assert_eq!(std::fs::read(dir.join("tiny.png")).unwrap(), OLD);
    assert_eq!(listing(&dir), ["bad.toml", "tiny.png", "tiny.toml"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Read-only files and files with more than one hard link are refused, naming the option;
/// symbolic links are followed and kept; a link to nothing is refused; a replaced file keeps its
/// permissions.
#[cfg(unix)]
#[test]
fn existing_outputs_are_replaced_only_as_documented() {
    use std::os::unix::fs::{symlink, PermissionsExt};
    let (dir, tiny) = setup(
        "targets",
        &["ro.png", "linked.png", "real.png", "private.png"],
    );
    let (d, t) = (dir.display(), tiny.display());
    let mode = |p: &str| std::fs::metadata(dir.join(p)).unwrap().permissions().mode() & 0o777;
    let chmod = |p: &str, m: u32| {
        std::fs::set_permissions(dir.join(p), std::fs::Permissions::from_mode(m)).unwrap()
    };
    chmod("ro.png", 0o444);
    std::fs::hard_link(dir.join("linked.png"), dir.join("other-name.png")).unwrap();
    symlink(dir.join("real.png"), dir.join("link.png")).unwrap();
    symlink(dir.join("missing.png"), dir.join("dangling.png")).unwrap();
    chmod("private.png", 0o600);
    assert_eq!(
        run(&format!("{t} --out {d}/ro.png")),
        Err(format!("--out {d}/ro.png: exists and is read-only: not replaced (make it writable, or name another file)"))
    );
    assert_eq!(
        run(&format!("{t} --out {d}/linked.png")),
        Err(format!("--out {d}/linked.png: has 2 hard links: not replaced, which would leave the other names with the old content (remove it first, or name another file)"))
    );
    assert_eq!(
        run(&format!("{t} --out {d}/dangling.png")),
        Err(format!("--out {d}/dangling.png: is a symbolic link to a missing file: not followed (remove the link, or name another file)"))
    );
    // Nothing changed so far.
    for f in ["ro.png", "linked.png", "other-name.png", "real.png"] {
        assert_eq!(std::fs::read(dir.join(f)).unwrap(), OLD, "{f}");
    }
    assert_eq!(mode("ro.png"), 0o444);
    // Through the link: the file it names is replaced, the link stays a link.
    assert_eq!(run(&format!("{t} --out {d}/link.png")), Ok(()));
    assert!(std::fs::symlink_metadata(dir.join("link.png"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read(dir.join("real.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    // Permissions are kept.
    assert_eq!(run(&format!("{t} --out {d}/private.png")), Ok(()));
    assert!(std::fs::read(dir.join("private.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    assert_eq!(mode("private.png"), 0o600);
    // Two names of one file through a linked directory are one file.
    std::fs::create_dir(dir.join("real")).unwrap();
    symlink(dir.join("real"), dir.join("alias")).unwrap();
    assert_eq!(
        run(&format!("{t} --out {d}/alias/a.pfm --pfm {d}/real/a.pfm")),
        Err(format!("{d}/alias/a.pfm and {d}/real/a.pfm are the same file ({}): refusing to write two outputs on it", canonical(&dir).join("real/a.pfm").display()))
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// No output is an input of the run: `--out` on the scene's texture, under any spelling or
/// through a link, is refused, and the texture stays as it was.
#[test]
fn an_input_is_never_written_over() {
    let (dir, _) = setup("inputs", &[]);
    let tex = dir.join("tex.png");
    image::RgbImage::from_pixel(4, 4, image::Rgb([200, 30, 30]))
        .save(&tex)
        .unwrap();
    let texture = std::fs::read(&tex).unwrap();
    let scene = dir.join("can.toml");
    let material = "type = \"image\"\nimage = \"tex.png\"";
    std::fs::write(&scene, one_object("", "", "", "", material)).unwrap();
    let (d, s) = (dir.display(), scene.display());
    let input = |shown: &str| {
        format!("{shown}: is a texture of can ({d}/tex.png): refusing to write over an input of the run")
    };
    assert_eq!(
        run(&format!("{s} --out {d}/tex.png")),
        Err(input(&format!("--out {d}/tex.png")))
    );
    assert_eq!(
        run(&format!("{s} --out {d}/./tex.png")),
        Err(input(&format!("--out {d}/./tex.png")))
    );
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&tex, dir.join("alias.png")).unwrap();
        assert_eq!(
            run(&format!("{s} --out {d}/alias.png")),
            Err(input(&format!("--out {d}/alias.png")))
        );
    }
    // A directory output whose picture would be the texture.
    std::fs::copy(&scene, dir.join("tex.toml")).unwrap();
    assert_eq!(
        run(&format!("{d}/tex.toml --out {d}")),
        Err(format!("{d}/tex.png: is a texture of tex ({d}/tex.png): refusing to write over an input of the run"))
    );
    assert_eq!(std::fs::read(&tex).unwrap(), texture);
    // One texture under two names is one input, loaded and counted once.
    let two = format!(
        "{}[[objects]]\nshape = \"cylinder\"\n[objects.material]\ntype = \"image\"\nimage = \"./tex.png\"\n",
        one_object("", "", "", "", material)
    );
    let scene = crate::scene::parse::<Flat>(&two, "two.toml", "two", &dir).unwrap();
    let texture = |i: usize| match &scene.materials[i].albedo {
        crate::material::Albedo::Image { texture, .. } => texture.clone(),
        other => panic!("{other:?}"),
    };
    assert!(std::sync::Arc::ptr_eq(&texture(0), &texture(1)));
    assert_eq!(scene.inputs.len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A commit that fails half-way (a directory it must create is taken by a file after the
/// outputs were written) puts back every output it had replaced and leaves no temporary.
#[test]
fn a_failed_commit_puts_everything_back() {
    let (dir, _) = setup("commit", &["a.png"]);
    let a = files::target(&dir.join("a.png"), Kind::Png, "--out").unwrap();
    let b = files::target(&dir.join("new/b.png"), Kind::Png, "--out").unwrap();
    let mut t = Transaction::default();
    for target in [&a, &b] {
        t.write(target, |w| {
            w.write_all(b"new content").map_err(|e| e.to_string())
        })
        .unwrap();
    }
    std::fs::write(dir.join("new"), b"in the way").unwrap();
    assert_eq!(
        t.commit(),
        Err(format!(
            "cannot write {}: Not a directory (os error 20)",
            dir.join("new/b.png").display()
        ))
    );
    assert_eq!(std::fs::read(dir.join("a.png")).unwrap(), OLD);
    assert_eq!(listing(&dir), ["a.png", "new", "tiny.toml"]);
    let _ = std::fs::remove_dir_all(&dir);
}
