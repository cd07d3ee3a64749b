//! A developed RGB image: what `mi.render` returns (§12): linear RGB, float32, row-major
//! with the top row first, already divided by the filter weight.

use glam::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// `width × height` pixels, row-major, top row first.
    pub pixels: Vec<Vec3>,
}

impl Image {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Image {
        Image { width, height, pixels: vec![Vec3::ZERO; width as usize * height as usize] }
    }

    /// Pixel (x, y), y = 0 being the top row.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    #[inline]
    pub fn set(&mut self, x: u32, y: u32, v: Vec3) {
        self.pixels[y as usize * self.width as usize + x as usize] = v;
    }
}
