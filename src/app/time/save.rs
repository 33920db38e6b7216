//! Ctrl+S: the world as it is now, written as an ordinary scene file.
//!
//! The file is `nudge-YYYYMMDD-HHMMSS.toml` in the save directory (`--save-dir`, else the working
//! directory). The time in the name is UTC: the standard library has no time-zone database and a
//! crate for one does not earn its place for a file name (`-2`, `-3`... follow if the name is taken).
//! Frozen bodies are saved as `frozen = true`: they load back frozen, not as scenery. See
//! `scene::write` for why it loads back bit for bit.

use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use crate::app::App;
use crate::scene::write::{scene_of_world, to_toml};

impl App {
    /// Writes the world to a new scene file; the status bar names it, or says why it could not.
    pub(crate) fn save_world(&mut self) {
        let dir = self
            .config
            .save_dir
            .clone()
            .unwrap_or_else(|| PathBuf::from("."));
        match self.write_world_into(&dir) {
            Ok(path) => {
                self.absorb_inputs();
                self.unsaved = false;
                self.say(format!("saved {}", path.display()));
            }
            Err(err) => self.say(format!("could not save into {}: {err}", dir.display())),
        }
    }

    /// The world as it is now, as a scene (bodies with their looks, and the camera): what Ctrl+S
    /// writes and what a recording starts from.
    pub(crate) fn scene_now(&self) -> crate::scene::Scene {
        let colors: Vec<_> = self.looks.iter().map(|l| l.color).collect();
        let scenery: Vec<bool> = self.looks.iter().map(|l| l.scenery).collect();
        let mut scene = scene_of_world(
            &self.scene.name,
            &self.world,
            &colors,
            &scenery,
            self.camera.get(),
        );
        // The scene's own bodies come first, in its order; the names go with them.
        for (saved, own) in scene.bodies.iter_mut().zip(&self.scene.bodies) {
            saved.name.clone_from(&own.name);
        }
        scene
    }

    /// Writes the world into a new file in `dir`; returns its path.
    pub fn write_world_into(&self, dir: &Path) -> std::io::Result<PathBuf> {
        let scene = self.scene_now();
        let step = self.world.step_count();
        let header = [
            &format!("nudge world saved from {} at step {step}", self.scene.name)[..],
            "load it with: nudge --scene FILE",
        ];
        let text = to_toml(&scene, &header);
        let stamp = utc_stamp(SystemTime::now());
        for n in 1.. {
            let name = if n == 1 {
                format!("nudge-{stamp}.toml")
            } else {
                format!("nudge-{stamp}-{n}.toml")
            };
            let path = dir.join(name);
            // `create_new`: never overwrite an earlier save from the same second.
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut file) => {
                    std::io::Write::write_all(&mut file, text.as_bytes())?;
                    return Ok(path);
                }
                Err(err) if err.kind() == std::io::ErrorKind::AlreadyExists && n < 100 => {}
                Err(err) => return Err(err),
            }
        }
        unreachable!("the loop returns")
    }
}

/// `YYYYMMDD-HHMMSS` in UTC.
pub fn utc_stamp(time: SystemTime) -> String {
    let secs = time.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    let (year, month, day) = civil_from_days(days as i64);
    format!(
        "{year:04}{month:02}{day:02}-{:02}{:02}{:02}",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

/// The proleptic Gregorian date of a day count since 1970-01-01 (Howard Hinnant's
/// `civil_from_days`: eras of 400 years, March-based years so the leap day comes last).
fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn utc_stamps_name_the_calendar_date_and_time() {
        assert_eq!(utc_stamp(UNIX_EPOCH), "19700101-000000");
        // 2000-02-29 (a leap day in a century year) 12:34:56.
        let t = UNIX_EPOCH + Duration::from_secs(951_827_696);
        assert_eq!(utc_stamp(t), "20000229-123456");
        // 2026-11-25 07:30:00.
        assert_eq!(
            utc_stamp(UNIX_EPOCH + Duration::from_secs(1_795_591_800)),
            "20261125-073000"
        );
    }
}
