//! The embedded store's directory: private to this server's user (the directory 0700, the
//! database files 0600), and held by one server at a time through an advisory lock
//! (`whirl.lock`, `flock`), released by the kernel when the process ends, however it ends.
//! The lock keeps other processes out; stores of one process on one directory share it (an
//! embedding program or a test suite may build several on one directory, and SQLite serves
//! them all).

use std::collections::HashMap;
use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, Write};
use std::os::unix::fs::{DirBuilderExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};

use super::StoreError;

/// The lock file in the data directory.
pub const LOCK: &str = "whirl.lock";

/// The locks this process holds, by canonical directory.
static HELD: Mutex<Option<HashMap<PathBuf, Weak<File>>>> = Mutex::new(None);

/// Creates the directory (0700) if needed and takes its lock, or shares this process's: an
/// error names the process that holds it. Keep the file for as long as the directory is used.
pub fn claim(dir: &Path) -> Result<Arc<File>, StoreError> {
    let mut held = HELD.lock().unwrap_or_else(|e| e.into_inner());
    let key = |d: &Path| d.canonicalize().unwrap_or_else(|_| d.to_path_buf());
    if let Some(file) = held
        .get_or_insert_with(HashMap::new)
        .get(&key(dir))
        .and_then(Weak::upgrade)
    {
        return Ok(file);
    }
    let file = Arc::new(lock(dir)?);
    let map = held.get_or_insert_with(HashMap::new);
    map.retain(|_, w| w.strong_count() > 0);
    map.insert(key(dir), Arc::downgrade(&file));
    Ok(file)
}

/// Takes the directory's lock for this process.
fn lock(dir: &Path) -> Result<File, StoreError> {
    let fail = |what: &str, e: std::io::Error| {
        StoreError(format!(
            "job store: cannot {what} WHIRL_DATA_DIR {}: {e}",
            dir.display()
        ))
    };
    std::fs::DirBuilder::new()
        .recursive(true)
        .mode(0o700)
        .create(dir)
        .map_err(|e| fail("create", e))?;
    let mut file = OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .mode(0o600)
        .open(dir.join(LOCK))
        .map_err(|e| fail("lock", e))?;
    if !try_lock(&file) {
        let mut holder = String::new();
        let _ = file.read_to_string(&mut holder);
        return Err(StoreError(format!(
            "job store: WHIRL_DATA_DIR {} is in use by another whirl server (process {}): \
             each server needs a data directory of its own; replicas share PostgreSQL \
             (WHIRL_DATABASE_URL)",
            dir.display(),
            holder.trim()
        )));
    }
    // Who holds it, for the message above.
    let _ = file.set_len(0);
    let _ = file.rewind();
    let _ = write!(file, "{}", std::process::id());
    Ok(file)
}

/// An exclusive `flock` without waiting.
fn try_lock(file: &File) -> bool {
    use std::os::fd::AsRawFd;
    // SAFETY: flock only reads the descriptor, which `file` keeps open.
    unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) == 0 }
}

/// Creates the database file 0600 before SQLite opens it (SQLite gives its WAL and shared
/// memory files the database file's mode), and narrows files an older version left open.
pub fn private_files(dir: &Path, file: &str) -> Result<(), StoreError> {
    let db = dir.join(file);
    OpenOptions::new()
        .append(true)
        .create(true)
        .mode(0o600)
        .open(&db)
        .map_err(|e| StoreError(format!("job store: cannot create {}: {e}", db.display())))?;
    for suffix in ["", "-wal", "-shm"] {
        let path = dir.join(format!("{file}{suffix}"));
        if let Ok(meta) = std::fs::metadata(&path)
            && meta.permissions().mode() & 0o077 != 0
        {
            let _ = std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o600));
        }
    }
    Ok(())
}
